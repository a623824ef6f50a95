#!/usr/bin/env bash
# The main job: builds mb_kinematics and shows it at work on the human body model: `mbk`, then
# the node live (launch/demo.launch, headless) with a short summary per body every second for
# a few seconds (or until Ctrl-C).
#   scripts/demo.sh [--seconds N] [--model FILE] [--rviz]
# --rviz opens rviz (installs it if missing; needs a display) and runs until Ctrl-C.
# It installs and builds only what it runs (the tests' packages and targets are scripts/test.sh's).
source "$(dirname "$0")/common.sh"
seconds=4
rviz=false
# mb_kinematics_msgs' Python messages: for rostopic in the README's quick start.
targets=(mbk mb_kinematics_node demo_publisher demo_monitor mb_kinematics_msgs_generate_messages_py
  mbk_python)  # the Python module (doc/python.md)
live_model="$MBK_SRC/config/human_body.yaml"
while [ $# -gt 0 ]; do
  case "$1" in
    --seconds) seconds=$2; shift 2 ;;
    --model) live_model=$(realpath "$2"); shift 2 ;;
    # rviz's RobotModel needs the URDF's frames (ball joints as chains of links).
    --rviz) rviz=true; seconds=0; live_model="$MBK_SRC/config/human_body.urdf"
      MBK_PACKAGES+=("${MBK_RVIZ_PACKAGES[@]}"); targets+=(mbk_rviz); shift ;;
    *) echo "usage: scripts/demo.sh [--seconds N] [--model FILE] [--rviz]" >&2; exit 2 ;;
  esac
done
mbk_install_deps
mbk_build "${targets[@]}"
model="$MBK_SRC/config/human_body.yaml"
echo "== mbk tables --model config/human_body.yaml"
rosrun mb_kinematics mbk tables --model "$model"
echo "== mbk eval --model config/human_body.yaml --state config/human_body_state.json"
rosrun mb_kinematics mbk eval --model "$model" --state "$MBK_SRC/config/human_body_state.json"

# The live demo, on a ROS master of its own (a free port, so other masters are left alone).
port=$(python3 -c 'import socket; s = socket.socket(); s.bind(("", 0)); print(s.getsockname()[1])')
export ROS_MASTER_URI=http://localhost:$port
log="$MBK_WS/demo_launch.log"
echo "== roslaunch mb_kinematics demo.launch model:=${live_model#"$MBK_SRC"/} (log: $log)"
stdbuf -oL roslaunch -p "$port" mb_kinematics demo.launch model:="$live_model" rviz:=$rviz >"$log" 2>&1 &
launch_pid=$!
stop() {
  kill -INT "$launch_pid" 2>/dev/null || true
  wait "$launch_pid" 2>/dev/null || true
}
trap 'stop; exit 130' INT TERM
set +e
for _ in $(seq 100); do  # the node logs its lower body arrays table once it is up
  grep -q "coordinates, max depth" "$log" && break
  kill -0 "$launch_pid" 2>/dev/null || break
  sleep 0.2
done
sed -n '/mb_kinematics: [0-9]* bodies/,/^bodies:/p' "$log" | sed 's/^.*\[ INFO\] \[[0-9.]*\]: //'
rosrun mb_kinematics demo_monitor _duration:="$seconds"
status=$?
stop
trap - INT TERM
exit "$status"
