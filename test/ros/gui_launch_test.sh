#!/usr/bin/env bash
# mb_kinematics.launch gui:=true on an Xvfb screen of its own and a ROS master of its own (a free
# port): joint_state_publisher_gui must start, publish joint_states, and the node turn them into
# body_kinematics. Fails with the launch's output if it cannot (`cannot launch node of type`
# when the package is not installed: scripts/common.sh installs it).
#   test/ros/gui_launch_test.sh    (in a sourced catkin workspace: devel/env.sh ...)
set -uo pipefail
src=$(cd "$(dirname "$0")/../.." && pwd)
fail() { echo "FAIL: $*" >&2; echo "--- roslaunch:" >&2; tail -n 30 "$tmp/launch.log" >&2; exit 1; }
# shellcheck source=../support/headless.sh
source "$src/test/support/headless.sh"
start_xvfb

port=$(free_port)
export ROS_MASTER_URI=http://localhost:$port
stdbuf -oL roslaunch -p "$port" mb_kinematics mb_kinematics.launch \
  model:="$src/test/robots/panda.urdf" gui:=true >"$tmp/launch.log" 2>&1 &
pids+=($!)
deadline=$((SECONDS + 40))
until grep -q "coordinates, max depth" "$tmp/launch.log" || [ $SECONDS -ge $deadline ]; do sleep 0.2; done
grep -q "cannot launch node" "$tmp/launch.log" && fail "a node of the launch could not start"
grep -q "coordinates, max depth" "$tmp/launch.log" || fail "the node did not start"

publishes() {  # (grep -q on a pipe would end rostopic early: pipefail)
  local info
  info=$(rostopic info /joint_states 2>/dev/null)
  grep -q "/joint_state_publisher_gui " <<<"$info"
}
until publishes || [ $SECONDS -ge $deadline ]; do
  grep -q "joint_state_publisher_gui.* process has died" "$tmp/launch.log" && break
  sleep 0.5
done
publishes || fail "joint_state_publisher_gui does not publish joint_states: $(rostopic info /joint_states 2>&1)"
timeout 20 rostopic echo -n 1 --noarr /joint_states >"$tmp/states" 2>&1 ||
  fail "no joint_states within 20 s"
timeout 20 rostopic echo -n 1 --noarr /body_kinematics >"$tmp/kinematics" 2>&1 ||
  fail "no body_kinematics from the GUI's joint_states within 20 s"
grep -q "frame_id: \"panda_link0\"" "$tmp/kinematics" || fail "body_kinematics: $(head "$tmp/kinematics")"
echo "PASS"
