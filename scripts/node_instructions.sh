#!/usr/bin/env bash
# Instructions per joint_states message of the node, or of transport_floor with --floor
# (doc/speed.md "The node's load"): callgrind counts the whole process over two run lengths of
# demo_publisher at RATE (default 50 Hz, 100-link random tree as scripts/node_load.sh's), with
# load_monitor listening to /tf and body_kinematics; the difference of the two counts over the
# difference of the messages is the cost of one message (start-up and shut-down cancel), for the
# joint_states callback (inclusive) and for the whole process. The callback's figure is the one to
# compare: under valgrind the spinner's and timers' threads cost per second of the (slowed) run,
# not per message, so the whole process's figure varies with the machine's load.
#
#   scripts/node_instructions.sh [--floor] [--rate HZ] [--seconds S] [--accelerations]
#                                [--port PORT]
#
# --seconds S (default 10): the shorter run; the longer one is 2 S. Builds nothing.
set -euo pipefail

RATE=50 SECONDS_=10 PORT=11473 BIN_NAME=mb_kinematics_node ACCEL=false
while [ $# -gt 0 ]; do
  case "$1" in
    --floor) BIN_NAME=transport_floor; shift ;;
    --rate) RATE=$2; shift 2 ;;
    --seconds) SECONDS_=$2; shift 2 ;;
    --accelerations) ACCEL=true; shift ;;
    --port) PORT=$2; shift 2 ;;
    *) echo "node_instructions.sh: unknown argument '$1' (see the header of $0)" >&2; exit 2 ;;
  esac
done

# shellcheck source=scripts/node_common.sh
source "$(dirname "${BASH_SOURCE[0]}")/node_common.sh"
node_script_env node_instructions "$PORT"
command -v valgrind >/dev/null || { echo "node_instructions.sh: needs valgrind" >&2; exit 1; }
stop() { kill -INT "$1" 2>/dev/null || true; wait "$1" 2>/dev/null || true; }
cleanup() {
  for ((i = ${#PIDS[@]} - 1; i >= 0; i--)); do stop "${PIDS[i]}"; done
  rm -rf "$TMP"
}
trap cleanup EXIT

random_tree_urdf 100 >"$TMP/tree.urdf"  # scripts/node_load.sh's tree
start_master "$PORT" "$TMP/tree.urdf"

# One run of S seconds: "instructions messages callback-instructions".
run() {
  valgrind --tool=callgrind --dump-instr=no --callgrind-out-file="$TMP/cg.$1" \
    "$BIN/$BIN_NAME" __name:=mb_kinematics >"$TMP/node.$1.log" 2>&1 &
  local node=$!
  for _ in $(seq 300); do rostopic list 2>/dev/null | grep -q body_kinematics && break; sleep 0.5; done
  "$BIN/load_monitor" _start:=0 _end:=$(($(date +%s) + 3600)) _tf:=true >"$TMP/mon.$1.log" 2>&1 &
  local monitor=$!
  sleep 3
  "$BIN/demo_publisher" _rate:="$RATE" _publish_accelerations:="$ACCEL" >"$TMP/pub.log" 2>&1 &
  local pub=$!
  sleep "$1"
  stop "$pub"
  sleep 2
  stop "$node"
  stop "$monitor"
  local total messages callback
  total=$(callgrind_annotate "$TMP/cg.$1" 2>/dev/null | awk '/PROGRAM TOTALS/ { gsub(",", "", $1); print $1 }')
  messages=$(callgrind_annotate --inclusive=yes "$TMP/cg.$1" 2>/dev/null |
    awk '/SubscriptionCallbackHelperT<boost::shared_ptr<sensor_msgs::JointState_/ { gsub(",", "", $1); print $1; exit }')
  callback=${messages:-0}
  messages=$(awk -F'[:,]' '/^joint_states/ { print $2 + 0 }' "$TMP/mon.$1.log")
  echo "$total $messages $callback"
}

echo "node_instructions: $BIN_NAME, 100-link tree, demo_publisher at $RATE Hz (joint_accelerations: $ACCEL)"
read -r i1 n1 c1 <<<"$(run "$SECONDS_")"
read -r i2 n2 c2 <<<"$(run $((2 * SECONDS_)))"
awk -v i1="$i1" -v n1="$n1" -v c1="$c1" -v i2="$i2" -v n2="$n2" -v c2="$c2" 'BEGIN {
  printf "runs of %d and %d messages, instructions per message: callback %.1fk, whole process %.1fk\n",
    n1, n2, (c2 - c1) / (n2 - n1) / 1000, (i2 - i1) / (n2 - n1) / 1000 }'
