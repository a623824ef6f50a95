#!/usr/bin/env bash
# Builds everything, checks the packaging (test/install/install_test.sh) and runs every test
# (unit, peer and integration) with ctest.
# Exits non-zero on any failure; the last line is ctest's summary.
source "$(dirname "$0")/common.sh"
mbk_install_deps
mbk_build
echo "== building tests"
(cd "$MBK_WS/build" && make -j2 tests >>"$MBK_WS/build.log" 2>&1) || {
  tail -n 60 "$MBK_WS/build.log"
  echo "test build failed: full log in $MBK_WS/build.log" >&2
  exit 1
}
"$MBK_SRC/test/install/install_test.sh" "$MBK_SRC" "$MBK_WS"
cd "$MBK_WS/build"
set +e
ctest --output-on-failure -j2 2>&1 | tee "$MBK_WS/ctest.log" | grep -v '^Total Test time'
status=${PIPESTATUS[0]}
exit "$status"
