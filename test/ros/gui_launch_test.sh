#!/usr/bin/env bash
# mb_kinematics.launch gui:=true on an Xvfb screen of its own and a ROS master of its own (a free
# port): joint_state_publisher_gui must start, publish joint_states, and the node turn them into
# body_kinematics. Fails with the launch's output if it cannot (`cannot launch node of type`
# when the package is not installed: scripts/common.sh installs it).
#   test/ros/gui_launch_test.sh    (in a sourced catkin workspace: devel/env.sh ...)
set -uo pipefail
src=$(cd "$(dirname "$0")/../.." && pwd)
tmp=$(mktemp -d "${TMPDIR:-/tmp}/mbk_gui_test.XXXXXX")
export ROS_HOME=$tmp/ros HOME=$tmp/home
mkdir -p "$HOME"
pids=()
stop() {  # the processes started here, newest first: SIGINT, then SIGKILL after 5 s
  local i p
  for ((i = ${#pids[@]} - 1; i >= 0; i--)); do
    p=${pids[i]}
    kill -INT "$p" 2>/dev/null || continue
    for _ in $(seq 50); do kill -0 "$p" 2>/dev/null || break; sleep 0.1; done
    kill -KILL "$p" 2>/dev/null
    wait "$p" 2>/dev/null
  done
  rm -rf "$tmp"
}
trap stop EXIT
trap 'exit 130' INT TERM
fail() { echo "FAIL: $*" >&2; echo "--- roslaunch:" >&2; tail -n 30 "$tmp/launch.log" >&2; exit 1; }

Xvfb -displayfd 3 -screen 0 1280x900x24 -nolisten tcp 3>"$tmp/display" >"$tmp/xvfb.log" 2>&1 &
pids+=($!)
for _ in $(seq 100); do [ -s "$tmp/display" ] && break; sleep 0.1; done
[ -s "$tmp/display" ] || fail "Xvfb did not start: $(cat "$tmp/xvfb.log")"
export DISPLAY=:$(head -n1 "$tmp/display")

port=$(python3 -c 'import socket; s = socket.socket(); s.bind(("", 0)); print(s.getsockname()[1])')
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
