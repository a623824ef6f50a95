#!/usr/bin/env bash
# Builds everything, checks the packaging (test/install/install_test.sh) and runs every test
# (unit, peer, integration, the fuzz smoke) with ctest.
# Exits non-zero on any failure; the last line is ctest's summary.
#   scripts/test.sh [--sanitize]
# --sanitize: the same build with -fsanitize=address,undefined (UB aborts, leaks fail, urdfdom's
# own leaks suppressed by test/lsan.supp) in a workspace of its own, <workspace>-sanitize; the
# rviz plugin and its screenshot test (rviz itself is not instrumented), the benchmarks (not
# tests), the fuzz smoke (its harnesses always are) and heap_trim_test (it measures glibc's
# malloc_trim, and ASan brings its own allocator) are left out, and it is built with -O1 -g
# (doc/reliability.md).
sanitize=${1:-}
[ -z "$sanitize" ] || [ "$sanitize" = --sanitize ] || { echo "usage: scripts/test.sh [--sanitize]" >&2; exit 2; }
source "$(dirname "$0")/common.sh"
build_args=()
skip=()
# ctest's slots: six on two cores (test/schedule.cmake: most tests wait, and a busy one takes
# two); two under the sanitizers, whose instrumented processes keep the cores busier.
jobs=6
if [ -n "$sanitize" ]; then
  MBK_WS=$MBK_WS-sanitize
  flags="-fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer"
  build_args=(-DCMAKE_CXX_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="$flags"
    -DCMAKE_SHARED_LINKER_FLAGS="$flags" -DCMAKE_CXX_FLAGS_RELEASE="-O1 -g -DNDEBUG"
    -DMBK_BENCHMARKS=OFF -DCMAKE_DISABLE_FIND_PACKAGE_rviz=ON)
  skip=(-E 'screenshot|fuzz_smoke|heap_trim')
  jobs=2
  export ASAN_OPTIONS=detect_leaks=1:abort_on_error=0
  export LSAN_OPTIONS=suppressions=$MBK_SRC/test/lsan.supp:print_suppressions=0
  export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
  # Debian's nodelet manager is not instrumented: the ASan runtime must come first when it loads
  # our library (test/ros/nodelet.test).
  export MBK_SANITIZER_PRELOAD="env LD_PRELOAD=$(g++ -print-file-name=libasan.so)"
fi
# The user + system CPU seconds of the processes this script has waited for, on each phase's
# line beside its wall seconds: a wall time on a shared machine says little alone
# (doc/building.md, "Where the time goes").
cpu_seconds() {  # /proc/PID/stat's cutime and cstime, in clock ticks
  awk -v hz="$(getconf CLK_TCK)" '{ printf "%.0f", ($16 + $17) / hz }' "/proc/$$/stat"
}
MBK_PACKAGES+=("${MBK_TEST_PACKAGES[@]}")
mbk_install_deps
mbk_build -DCATKIN_ENABLE_TESTING=ON "${build_args[@]}"
echo "== building tests (${SECONDS} s in, $(cpu_seconds) CPU s)"
# The fuzz harnesses' clang build (scripts/fuzz.sh --build) beside the tests' build: ctest's
# fuzz_smoke, the longest test, then waits for it (a lock) rather than starting it; its output
# is in <workspace>/fuzz/build.log, and a failed build fails fuzz_smoke, which builds again.
fuzz_build=
if [ -z "$sanitize" ]; then
  MBK_WS=$MBK_WS setsid "$MBK_SRC/scripts/fuzz.sh" --build >/dev/null 2>&1 &
  fuzz_build=$!
  trap '[ -z "$fuzz_build" ] || kill -- -"$fuzz_build" 2>/dev/null || true' EXIT
fi
# The install check first, beside the fuzz build: its steps run one at a time (catkin's
# configure, the downstream package's two builds), so the fuzz build has the other core; the
# package it installs is built, and the tests' build after it compiles nothing of it again.
[ -n "$sanitize" ] || "$MBK_SRC/test/install/install_test.sh" "$MBK_SRC" "$MBK_WS"
(cd "$MBK_WS/build" && make -j2 tests >>"$MBK_WS/build.log" 2>&1) || {
  tail -n 60 "$MBK_WS/build.log"
  echo "test build failed: full log in $MBK_WS/build.log" >&2
  exit 1
}
echo "== ctest (${SECONDS} s in, $(cpu_seconds) CPU s)"
cd "$MBK_WS/build"
set +e
ctest --output-on-failure -j"$jobs" "${skip[@]}" 2>&1 | tee "$MBK_WS/ctest.log" | grep -v '^Total Test time'
status=${PIPESTATUS[0]}
exit "$status"
