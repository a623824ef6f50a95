#!/usr/bin/env bash
# test/rviz/legend_reset_test.cc on an Xvfb screen and a ROS master of its own (rviz's
# VisualizationManager needs both):
#   test/rviz/legend_reset_test.sh TEST_BINARY [GTEST_ARGS...]   (in a sourced catkin workspace)
set -uo pipefail
binary=${1:?usage: legend_reset_test.sh TEST_BINARY [GTEST_ARGS...]}
shift
src=$(cd "$(dirname "$0")/../.." && pwd)
fail() { echo "FAIL: $*" >&2; exit 1; }
# shellcheck source=../support/headless.sh
source "$src/test/support/headless.sh"
start_xvfb
port=$(free_port)
export ROS_MASTER_URI=http://localhost:$port
rosmaster --core -p "$port" >"$tmp/master.log" 2>&1 &
pids+=($!)
for _ in $(seq 100); do rostopic list >/dev/null 2>&1 && break; sleep 0.1; done
rostopic list >/dev/null 2>&1 || fail "the ROS master did not start: $(tail "$tmp/master.log")"
"$binary" "$@"
