#!/usr/bin/env bash
# The node's load against robot_state_publisher on the same stream (doc/speed.md "The node's load"):
# its own master (roscore -p PORT on 127.0.0.1, stopped at the end), mb_kinematics_node,
# robot_state_publisher (_ignore_timestamp:=true: tf for every sample), demo_publisher at RATE
# on MODEL, and load_monitor (subscribed to body_kinematics and /tf; it counts the messages whose
# stamps lie in the window, so that one delayed at the window's edges is not taken for one
# lost, and ends 1 s after the window, for those still on their way). After a warm-up it reads
# /proc/<pid>/stat of the node and of robot_state_publisher over a window, and prints both CPU
# shares (% of one core), their ratio, the node's RSS and the message rates received; with /tf
# listened also the CPU per sample each one published (us per /tf message: robot_state_publisher
# subscribes joint_states with a queue of 1 and skips the samples that arrive while it works).
#
#   scripts/node_load.sh [--rate HZ] [--bodies N | --model FILE.urdf] [--seconds S]
#                        [--warmup S] [--runs R] [--port PORT] [--nodelet]
#                        [--accelerations] [--no-tf-listener] [--floor]
#
# --bodies N (default 100) writes a random tree of N links on continuous joints (seeded, so
# every run loads the same URDF). --runs R repeats the measurement and prints the medians.
# --nodelet runs the node as a nodelet in a manager (the manager's CPU is measured).
# demo_publisher sends joint_states with velocities, the stream robot_state_publisher gets;
# --accelerations adds its joint_accelerations (the node then estimates nothing).
# --no-tf-listener: load_monitor leaves /tf unsubscribed (nobody then serializes tf).
# --floor: transport_floor in place of the node: the same input and messages, no computation
# (what roscpp alone costs per sample; its CPU is printed as the node's).
# Builds nothing: run scripts/test.sh (or mbk_build) first.
set -euo pipefail

RATE=1000 BODIES=100 MODEL="" SECONDS_=10 WARMUP=5 RUNS=1 PORT=11471 NODELET=0 ACCEL=false TF=true
FLOOR=0
while [ $# -gt 0 ]; do
  case "$1" in
    --rate) RATE=$2; shift 2 ;;
    --bodies) BODIES=$2; shift 2 ;;
    --model) MODEL=$2; shift 2 ;;
    --seconds) SECONDS_=$2; shift 2 ;;
    --warmup) WARMUP=$2; shift 2 ;;
    --runs) RUNS=$2; shift 2 ;;
    --port) PORT=$2; shift 2 ;;
    --nodelet) NODELET=1; shift ;;
    --accelerations) ACCEL=true; shift ;;
    --no-tf-listener) TF=false; shift ;;
    --floor) FLOOR=1; shift ;;
    *) echo "node_load.sh: unknown argument '$1' (see the header of $0)" >&2; exit 2 ;;
  esac
done

# shellcheck source=scripts/node_common.sh
source "$(dirname "${BASH_SOURCE[0]}")/node_common.sh"
node_script_env node_load "$PORT"
cleanup() {
  for ((i = ${#PIDS[@]} - 1; i >= 0; i--)); do kill -INT "${PIDS[i]}" 2>/dev/null || true; done
  for _ in $(seq 50); do
    alive=0
    for p in "${PIDS[@]}"; do kill -0 "$p" 2>/dev/null && alive=1; done
    [ "$alive" = 0 ] && break
    sleep 0.1
  done
  for p in "${PIDS[@]}"; do kill -KILL "$p" 2>/dev/null || true; done
  rm -rf "$TMP"
}
trap cleanup EXIT

if [ -z "$MODEL" ]; then
  MODEL=$TMP/tree$BODIES.urdf
  random_tree_urdf "$BODIES" >"$MODEL"
fi

start_master "$PORT" "$MODEL"

NODE_NAME=/mb_kinematics  # the publisher of the node's /tf
if [ "$NODELET" = 1 ]; then
  NODE_NAME=/manager
  /usr/lib/nodelet/nodelet manager __name:=manager >"$TMP/node.log" 2>&1 &
  NODE=$!
  /usr/lib/nodelet/nodelet load mb_kinematics/KinematicsNodelet manager __name:=mb_kinematics \
    >"$TMP/load.log" 2>&1 &
  PIDS+=($NODE $!)
elif [ "$FLOOR" = 1 ]; then
  "$BIN/transport_floor" __name:=mb_kinematics >"$TMP/node.log" 2>&1 &
  NODE=$!
  PIDS+=($NODE)
else
  "$BIN/mb_kinematics_node" __name:=mb_kinematics >"$TMP/node.log" 2>&1 &
  NODE=$!
  PIDS+=($NODE)
fi
rosrun robot_state_publisher robot_state_publisher _ignore_timestamp:=true \
  __name:=robot_state_publisher >"$TMP/rsp.log" 2>&1 &
RSP=$!
PIDS+=($RSP)

# utime + stime of a process, in clock ticks (fields 14 and 15 of /proc/<pid>/stat).
ticks() { awk '{ sub(/.*\) /, ""); print $12 + $13 }' "/proc/$1/stat"; }
rss_mb() { awk '/VmRSS/ { printf "%.1f", $2 / 1024 }' "/proc/$1/status"; }
median() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
HZ=$(getconf CLK_TCK)

echo "node_load: $([ "$FLOOR" = 1 ] && echo "transport_floor in place of the node, ")$(grep -c '<link' "$MODEL") links, demo_publisher at $RATE Hz (joint_accelerations: $ACCEL), /tf listened: $TF, window $SECONDS_ s after $WARMUP s, $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg)"
for run in $(seq "$RUNS"); do
  "$BIN/demo_publisher" _rate:="$RATE" _publish_accelerations:="$ACCEL" >"$TMP/pub.log" 2>&1 &
  PUB=$!
  start=$(awk -v w="$WARMUP" '{ printf "%.3f", $1 + w }' <<<"$(date +%s.%N)")
  end=$(awk -v s="$SECONDS_" '{ printf "%.3f", $1 + s }' <<<"$start")
  "$BIN/load_monitor" _start:="$start" _end:="$end" _tf:="$TF" >"$TMP/monitor.log" 2>&1 &
  MON=$!
  sleep "$WARMUP"
  n0=$(ticks "$NODE") r0=$(ticks "$RSP") t0=$(date +%s.%N)
  sleep "$SECONDS_"
  n1=$(ticks "$NODE") r1=$(ticks "$RSP") t1=$(date +%s.%N)
  wait "$MON" || true
  kill -INT "$PUB"
  wait "$PUB" || true
  node=$(awk -v a="$n0" -v b="$n1" -v s="$t0" -v e="$t1" -v hz="$HZ" 'BEGIN { printf "%.1f", 100 * (b - a) / hz / (e - s) }')
  rsp=$(awk -v a="$r0" -v b="$r1" -v s="$t0" -v e="$t1" -v hz="$HZ" 'BEGIN { printf "%.1f", 100 * (b - a) / hz / (e - s) }')
  ratio=$(awk -v n="$node" -v r="$rsp" 'BEGIN { printf "%.2f", (r > 0) ? n / r : 0 }')
  bk=$(awk -F'[:,]' '/^body_kinematics/ { print $2 + 0 }' "$TMP/monitor.log")
  js=$(awk -F'[:,]' '/^joint_states/ { print $2 + 0 }' "$TMP/monitor.log")
  tf_node=$(awk -F'[:,]' -v n="/tf from $NODE_NAME" 'index($0, n) == 1 { print $2 + 0 }' "$TMP/monitor.log")
  tf_rsp=$(awk -F'[:,]' '/^\/tf from \/robot_state_publisher/ { print $2 + 0 }' "$TMP/monitor.log")
  per=$(awk -v n="$node" -v r="$rsp" -v a="${tf_node:-0}" -v b="${tf_rsp:-0}" -v s="$SECONDS_" 'BEGIN {
    if (a > 0 && b > 0) printf "%.0f %.0f %.2f", n * s * 1e4 / a, r * s * 1e4 / b, (n / a) / (r / b); else print "- - -" }')
  echo "run $run: node ${node} % of a core, robot_state_publisher ${rsp} %, ratio ${ratio}; node RSS $(rss_mb "$NODE") MB"
  read -r per_node per_rsp per_ratio <<<"$per"
  echo "  CPU per published sample: node ${per_node} us, robot_state_publisher ${per_rsp} us, ratio ${per_ratio}"
  sed 's/^/  /' "$TMP/monitor.log"
  echo "  body_kinematics messages / joint_states messages: ${bk:-0} / ${js:-0}"
  echo "$node $rsp $ratio $per_ratio" >>"$TMP/runs"
  sleep 1
done
if [ "$RUNS" -gt 1 ]; then
  echo "medians of $RUNS runs: node $(cut -d' ' -f1 "$TMP/runs" | median) %," \
    "robot_state_publisher $(cut -d' ' -f2 "$TMP/runs" | median) %, ratio $(cut -d' ' -f3 "$TMP/runs" | median);" \
    "ratio per published sample $(cut -d' ' -f4 "$TMP/runs" | median)"
fi
