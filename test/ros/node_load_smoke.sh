#!/usr/bin/env bash
# scripts/node_load.sh end to end, short and slow (doc/speed.md "The node's load"): the node, then
# transport_floor in its place (--floor), each at 200 Hz on a 20-body tree. Fails unless each
# run prints its CPU shares and load_monitor counted every joint_states sample of the window on
# body_kinematics and on the node's /tf.
set -euo pipefail
src=$(cd "$(dirname "$0")/../.." && pwd)
status=0
for mode in "" --floor; do
  out=$("$src/scripts/node_load.sh" --rate 200 --bodies 20 --seconds 2 --warmup 2 --port 11523 \
    $mode 2>&1) || { echo "$out"; echo "FAIL: node_load.sh $mode exited non-zero"; exit 1; }
  echo "$out"
  js=$(awk -F'[:,]' '/^  joint_states:/ { print $2 + 0 }' <<<"$out")
  bk=$(awk -F'[:,]' '/^  body_kinematics:/ { print $2 + 0 }' <<<"$out")
  tf=$(awk -F'[:,]' '/^  \/tf from \/mb_kinematics:/ { print $2 + 0 }' <<<"$out")
  grep -Eq '^run 1: node [0-9.]+ % of a core, robot_state_publisher [0-9.]+ %' <<<"$out" ||
    { echo "FAIL ($mode): no CPU shares"; status=1; }
  [ "${js:-0}" -ge 300 ] || { echo "FAIL ($mode): joint_states counted ${js:-0} (< 300)"; status=1; }
  [ "${bk:-0}" = "${js:-0}" ] || { echo "FAIL ($mode): body_kinematics ${bk:-0} of ${js:-0}"; status=1; }
  [ "${tf:-0}" = "${js:-0}" ] || { echo "FAIL ($mode): /tf ${tf:-0} of ${js:-0}"; status=1; }
done
[ "$status" = 0 ] && echo "node_load smoke: passed"
exit "$status"
