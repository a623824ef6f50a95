#!/usr/bin/env bash
# Fuzzes the loaders with libFuzzer (doc/reliability.md): builds test/fuzz/ with clang-14
# (ASan, UBSan, LeakSanitizer) outside catkin, then runs each harness for SECONDS seconds
# (default 60) on its corpus, seeded from the shipped configs and test/io/data, plus the inputs
# of past findings (test/fuzz/regressions/<harness>/). Any crash, hang (10 s), leak or sanitizer
# report fails it; the input is kept in <fuzz dir>/findings/.
#   scripts/fuzz.sh [seconds]     all harnesses, SECONDS each
#   scripts/fuzz.sh --smoke       what scripts/test.sh runs (ctest fuzz_smoke): a fixed seed and
#                                 a fixed number of runs per harness (smoke_runs), so that CI
#                                 replays the same inputs every time; new ground is for the
#                                 timed runs
#   scripts/fuzz.sh --build       only build the harnesses
source "$(dirname "$0")/common.sh"
seconds=60
mode=run
case "${1:-}" in
  --smoke) mode=smoke seconds=60 ;;  # the smoke's corpus is the seeds alone (see below)
  --build) mode=build ;;
  [0-9]*) seconds=$1 ;;
  "") ;;
  *) echo "usage: scripts/fuzz.sh [seconds | --smoke | --build]" >&2; exit 2 ;;
esac
# The slowest smoke first (bag 108 s, mjcf 61, sdf 48, glyphs 23, the others 9 to 14 in a clean
# clone's ctest), so that the harnesses running two at a time end together.
harnesses=(bag mjcf sdf glyphs recording joint_state_input state_json yaml_scene lower urdf)
dir=${MBK_FUZZ_DIR:-$MBK_WS/fuzz}
mkdir -p "$dir/build" "$dir/findings"

# The generated mb_kinematics_msgs headers come from the catkin build (scripts/test.sh's).
[ -f "$MBK_WS/devel/include/mb_kinematics_msgs/JointAccelerations.h" ] || mbk_build mb_kinematics_msgs_generate_messages_cpp
# One build at a time in the folder: scripts/test.sh starts one beside the tests' build, and
# ctest's fuzz_smoke waits for it here, then finds the harnesses built.
exec 9>"$dir/build.lock"
flock 9
# The physical paths: ctest runs this script through the workspace's src/ link, and another
# source path would make CMake compile everything again.
(cmake -S "$(cd "$MBK_SRC" && pwd -P)/test/fuzz" -B "$dir/build" -DCMAKE_C_COMPILER=clang-14 \
   -DCMAKE_CXX_COMPILER=clang++-14 -DMBK_DEVEL_INCLUDE="$(cd "$MBK_WS" && pwd -P)/devel/include" &&
   cmake --build "$dir/build" -j2) >"$dir/build.log" 2>&1 || {
  tail -n 40 "$dir/build.log"
  echo "fuzz build failed: full log in $dir/build.log" >&2
  exit 1
}
exec 9>&-
[ "$mode" = build ] && exit 0

smoke_runs() {  # about 5 s each on this project's 2-core CI machines
  case "$1" in
    urdf | yaml_scene) echo 5000 ;;
    state_json) echo 10000 ;;
    joint_state_input) echo 3000 ;;
    lower) echo 100000 ;;
    bag) echo 1500 ;;  # each input is read twice (bag_input.cc: once in a child process)
    glyphs) echo 5000 ;;
    mjcf) echo 2000 ;;
    sdf) echo 200 ;;  # sdformat is slow: 2000 runs took 314 s here (at load 20)
    recording) echo 2000 ;;
  esac
}

seeds() {  # the shipped files each harness starts from
  case "$1" in
    urdf) ls "$MBK_SRC"/config/*.urdf "$MBK_SRC"/test/ros/*.urdf ;;
    yaml_scene) ls "$MBK_SRC"/config/*.yaml "$MBK_SRC"/test/io/data/*.yaml ;;
    state_json | joint_state_input) ls "$MBK_SRC"/config/*.json "$MBK_SRC"/test/io/data/*.json ;;
    lower) ls "$MBK_SRC"/test/fuzz/seeds/lower/* ;;
    bag) ls "$MBK_SRC"/test/fuzz/seeds/bag/* ;;
    glyphs) ls "$MBK_SRC"/test/fuzz/seeds/glyphs/* ;;
    mjcf) ls "$MBK_SRC"/test/robots/mjcf/*.xml ;;
    sdf) ls "$MBK_SRC"/test/robots/sdf/*.sdf ;;
    recording) ls "$MBK_SRC"/test/fuzz/seeds/recording/* ;;
  esac
}

export ASAN_OPTIONS=detect_leaks=1:allocator_may_return_null=1
# clang-14's runtime names functions only through llvm-symbolizer, which is not on PATH under
# that name without Debian's unversioned llvm package.
symbolizer=/usr/lib/llvm-14/bin/llvm-symbolizer
[ -x "$symbolizer" ] && export ASAN_SYMBOLIZER_PATH=$symbolizer
export LSAN_OPTIONS=suppressions=$MBK_SRC/test/lsan.supp:print_suppressions=0
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
# fuzz_one HARNESS: runs it, writes its line of the summary to <fuzz dir>/HARNESS.result; fails
# on a finding.
fuzz_one() {
  local h=$1 corpus="$dir/corpus/$1"  # grows from run to run; the smoke starts from the seeds
  local limits=(-max_total_time="$seconds") log="$dir/$1.log" status runs
  if [ "$mode" = smoke ]; then
    corpus="$dir/smoke/$h" && rm -rf "$corpus"
    limits+=(-seed=1 -runs="$(smoke_runs "$h")")
  fi
  mkdir -p "$corpus"
  seeds "$h" | xargs -I{} cp {} "$corpus/"
  local regressions="$MBK_SRC/test/fuzz/regressions/$h"
  [ -d "$regressions" ] && cp "$regressions"/* "$corpus/" 2>/dev/null
  # A hang is an input over -timeout seconds. A bag whose record declares 1 GB makes librosbag
  # allocate it before reading: 4 to 6 s under ASan on an idle core (0.15 s without), over 10 s
  # on a busy one; the bag harness gets 30.
  local timeout=10
  [ "$h" = bag ] && timeout=30
  "$dir/build/${h}_fuzzer" "$corpus" "${limits[@]}" -timeout="$timeout" -rss_limit_mb=2048 \
    -max_len=65536 -print_final_stats=1 -artifact_prefix="$dir/findings/$h-" >"$log" 2>&1
  status=$?
  runs=$(awk '/stat::number_of_executed_units/ {print $2}' "$log")
  if [ "$status" -ne 0 ]; then
    { echo "fuzz $h: FINDING after ${runs:-?} runs (exit $status): $(grep -m1 -E 'ERROR|finding|deadly|timeout|leak' "$log")"
      echo "  log: $log; input: $(ls -t "$dir"/findings/"$h"-* 2>/dev/null | head -n 1)"
    } >"$dir/$h.result"
    return 1
  fi
  echo "fuzz $h: ${runs:-?} runs, corpus $(ls "$corpus" | wc -l) inputs, no finding" >"$dir/$h.result"
}

set +e
# Two harnesses at a time (each is one process on one core; MBK_FUZZ_JOBS to change), their
# lines in the harnesses' order.
jobs_at_once=${MBK_FUZZ_JOBS:-2}
for h in "${harnesses[@]}"; do
  while [ "$(jobs -rp | wc -l)" -ge "$jobs_at_once" ]; do wait -n; done
  rm -f "$dir/$h.result"
  fuzz_one "$h" &
done
wait
failed=0
for h in "${harnesses[@]}"; do
  cat "$dir/$h.result" 2>/dev/null || echo "fuzz $h: no result (see $dir/$h.log)"
  grep -q "no finding$" "$dir/$h.result" 2>/dev/null || failed=$((failed + 1))
done
# The Python module's out= arrays (test/fuzz/python_out_fuzz.py): a random search of its own on
# the workspace's package (the module is not instrumented); the smoke a fixed seed and count.
python_fuzz=(--seconds "$seconds")
[ "$mode" = smoke ] && python_fuzz=(--runs 2000 --seed 1)
if PYTHONPATH="$MBK_WS/devel/lib/python3/dist-packages${PYTHONPATH:+:$PYTHONPATH}" \
   /usr/bin/python3 "$MBK_SRC/test/fuzz/python_out_fuzz.py" "${python_fuzz[@]}" >"$dir/python_out.log" 2>&1; then
  echo "fuzz python_out: $(tail -n 1 "$dir/python_out.log")"
else
  failed=$((failed + 1))
  echo "fuzz python_out: FINDING: $(tail -n 1 "$dir/python_out.log"); log: $dir/python_out.log"
fi
echo "$(( ${#harnesses[@]} + 1 - failed )) passed, $failed failed"
[ "$failed" -eq 0 ]
