#!/bin/bash
# Instructions per update of the recursion (forward_kinematics) on kinematics_benchmark's scenes at
# each level, and of partial_velocity_kinematics on two of them: callgrind counts a run of 200
# updates and one of 100 (bench/recursion_instructions.cc); their difference / 100 leaves out
# loading and start-up. Deterministic: the same binaries give the same counts. doc/speed.md
# "Instructions per update".
#   bench/recursion_instructions.sh DEVEL_LIB_DIR
set -euo pipefail
driver=${1:?usage: recursion_instructions.sh DEVEL_LIB_DIR}/recursion_instructions
count() {  # count SCENE FORMULATION LEVEL N: instructions of the whole run
  valgrind --tool=callgrind --callgrind-out-file=/dev/null "$driver" "$@" 2>&1 >/dev/null |
    sed -n 's/.*Collected : \([0-9]*\).*/\1/p'
}
per_update() {  # per_update SCENE FORMULATION LEVEL
  echo "$1 $2 $3 $((($(count "$@" 200) - $(count "$@" 100)) / 100))"
}
for scene in human human_urdf humanoid29 random64 tree100 chain10 chain100 chain1000; do
  for level in pose velocity full; do per_update $scene recursive $level; done
done
for scene in human tree100; do
  for level in pose full; do per_update $scene pv $level; done
done
