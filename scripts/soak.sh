#!/usr/bin/env bash
# A soak of the node: mb_kinematics_node on the human model at 1 kHz (demo_publisher, with
# joint_accelerations) with a body_kinematics subscriber (demo_monitor), for MINUTES minutes on
# a ROS master of its own. Every 30 s it prints the node's resident memory (RSS) and its CPU
# share over the last interval, and at the end whether RSS stayed flat: exit 1 if RSS grew by
# more than 1 MiB between the first and the last sample (allocator noise is well below that).
#   scripts/soak.sh [minutes] [--model FILE] [--rate HZ] [--interval S]
source "$(dirname "$0")/common.sh"
minutes=10
model="$MBK_SRC/config/human_body.urdf"
rate=1000
interval=30
while [ $# -gt 0 ]; do
  case "$1" in
    --model) model=$(realpath "$2"); shift 2 ;;
    --rate) rate=$2; shift 2 ;;
    --interval) interval=$2; shift 2 ;;
    [0-9]*) minutes=$1; shift ;;
    *) echo "usage: scripts/soak.sh [minutes] [--model FILE] [--rate HZ] [--interval S]" >&2; exit 2 ;;
  esac
done
mbk_install_deps
mbk_build mb_kinematics_node demo_publisher demo_monitor

port=$(python3 -c 'import socket; s = socket.socket(); s.bind(("", 0)); print(s.getsockname()[1])')
export ROS_MASTER_URI=http://127.0.0.1:$port ROS_HOSTNAME=127.0.0.1
log="$MBK_WS/soak"
mkdir -p "$log"
pids=()
stop() {
  for p in "${pids[@]}"; do kill -INT "$p" 2>/dev/null || true; done
  for p in "${pids[@]}"; do wait "$p" 2>/dev/null || true; done
}
trap 'stop; exit 130' INT TERM
roscore -p "$port" >"$log/roscore.log" 2>&1 &
pids+=($!)
for _ in $(seq 100); do rostopic list >/dev/null 2>&1 && break; sleep 0.2; done
case "$model" in
  *.urdf | *.xml) rosparam set robot_description -t "$model"; model_param=() ;;
  *) model_param=(_model:="$model") ;;
esac
rosrun mb_kinematics mb_kinematics_node "${model_param[@]}" >"$log/node.log" 2>&1 &
node=$!
pids+=("$node")
rosrun mb_kinematics demo_publisher "${model_param[@]}" _rate:="$rate" >"$log/publisher.log" 2>&1 &
pids+=($!)
rosrun mb_kinematics demo_monitor _period:="$interval" >"$log/monitor.log" 2>&1 &
pids+=($!)

# The node's own process (rosrun execs it), its RSS (kB) and CPU ticks.
rss_kb() { awk '/^VmRSS/ {print $2}' "/proc/$node/status"; }
ticks() { awk '{print $14 + $15}' "/proc/$node/stat"; }
hz=$(getconf CLK_TCK)
samples=$((minutes * 60 / interval))
echo "== soak: $(basename "$model") at $rate Hz for $minutes min, node pid $node (logs: $log)"
printf '%8s %10s %8s\n' "t (s)" "RSS (MiB)" "CPU (%)"
sleep 2
first=""
last=""
t0=$(date +%s.%N)
c0=$(ticks)
set +e
for i in $(seq "$samples"); do
  sleep "$interval"
  if ! kill -0 "$node" 2>/dev/null; then
    echo "soak: the node died (see $log/node.log)" >&2
    stop
    exit 1
  fi
  t1=$(date +%s.%N)
  c1=$(ticks)
  rss=$(rss_kb)
  awk -v t="$((i * interval))" -v rss="$rss" -v c="$((c1 - c0))" -v hz="$hz" -v t0="$t0" \
    -v t1="$t1" 'BEGIN {printf "%8d %10.2f %8.1f\n", t, rss / 1024, 100 * c / hz / (t1 - t0)}'
  [ -n "$first" ] || first=$rss
  last=$rss
  t0=$t1
  c0=$c1
done
published=$(grep -c "body_kinematics at" "$log/monitor.log")
echo "monitor saw body_kinematics in $published of $samples intervals; last: $(grep "body_kinematics at" "$log/monitor.log" | tail -n 1)"
stop
trap - INT TERM
growth=$((last - first))
echo "RSS growth from the first to the last sample: ${growth} kB"
if [ "$growth" -gt 1024 ]; then
  echo "soak: RSS grew by more than 1 MiB" >&2
  exit 1
fi
echo "soak: RSS flat"
