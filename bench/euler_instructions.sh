#!/bin/bash
# Instructions per update of the human scene with its ball and free joints' angles in each Euler
# order, and the ratio to 1-2-3 (XYZ): callgrind counts a run of 200 updates and one of 100
# (bench/recursion_instructions.cc, scene human:ORDER); their difference / 100 leaves out loading and start-up.
# Deterministic: the same binary gives the same counts. doc/speed.md "Euler orders".
#   bench/euler_instructions.sh DEVEL_LIB_DIR [ORDER...]   (default: XYZ ZYX ZXZ)
set -euo pipefail
driver=${1:?usage: euler_instructions.sh DEVEL_LIB_DIR [ORDER...]}/recursion_instructions
shift
orders=("$@")
[ $# -gt 0 ] || orders=(XYZ ZYX ZXZ)
count() {  # count ORDER FORMULATION LEVEL N: instructions of the whole run
  valgrind --tool=callgrind --callgrind-out-file=/dev/null "$driver" "human:$1" "${@:2}" 2>&1 >/dev/null |
    sed -n 's/.*Collected : \([0-9]*\).*/\1/p'
}
printf '%-11s %-6s' formulation level
for o in "${orders[@]}"; do printf ' %8s %6s' "$o" ratio; done
echo
for formulation in recursive pv; do
  for level in pose full; do
    printf '%-11s %-6s' "$formulation" "$level"
    base=
    for o in "${orders[@]}"; do
      per=$((($(count "$o" $formulation $level 200) - $(count "$o" $formulation $level 100)) / 100))
      [ -n "$base" ] || base=$per
      printf ' %8d %6s' "$per" "$(awk -v a="$per" -v b="$base" 'BEGIN { printf "%.3f", a / b }')"
    done
    echo
  done
done
