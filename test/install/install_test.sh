#!/usr/bin/env bash
# Packaging, checked the way a ROS packager would (doc/building.md): catkin_lint finds no
# error in either package; `catkin_make install` of the workspace; then, from install/setup.bash
# alone (a clean environment), `rosrun mb_kinematics mbk`, `rosmsg show mb_kinematics_msgs/...`,
# the Python module (`import mb_kinematics`, a model's kinematics) and test/downstream (a package using the core's headers and library and the messages), built
# and installed in the same workspace and run from its install space; then built again in a
# workspace of its own on top of the install space alone, and run. Output in WS/install_test.log.
#   test/install/install_test.sh SRC WS
set -euo pipefail
src=${1:?usage: install_test.sh SRC WS} ws=${2:?usage: install_test.sh SRC WS}
log=$ws/install_test.log
fail() { tail -n 30 "$log"; echo "install test failed: $* (full log: $log)" >&2; exit 1; }
(cd "$src" && catkin_lint -q . mb_kinematics_msgs) >"$log" 2>&1 || fail "catkin_lint found errors"
ln -sfn "$src/test/downstream" "$ws/src/mbk_downstream"  # a package of the same workspace
# A clean environment, so that the install space chains to no devel space.
env -i HOME="$HOME" PATH=/usr/bin:/bin bash -c 'cd "$1" && catkin_make --force-cmake install -j2' _ "$ws" \
  >>"$log" 2>&1 || fail "catkin_make install"
env -i HOME="$HOME" PATH=/usr/bin:/bin bash -euo pipefail -c '
  set +u  # the setup scripts of catkin read unset variables
  source "$1/install/setup.bash"
  set -u
  tables=$(rosrun mb_kinematics mbk tables --lower 0,1,2,1)
  [[ $tables == *"L^1(k)"* ]]
  msg=$(rosmsg show mb_kinematics_msgs/BodyKinematics)
  [[ $msg == *"geometry_msgs/Twist twist"* ]]
  rosrun mbk_downstream mbk_downstream
  cd "$1"  # not the source tree, whose C++ folder mb_kinematics/ would shadow the package
  /usr/bin/python3 -c "import sys, mb_kinematics; m = mb_kinematics.load(sys.argv[1]); \
    assert m.kinematics(m.neutral_position)[\"rotation\"].shape == (10, 3, 3)" \
    "$(rospack find mb_kinematics)/config/ten_body.yaml"
  down=$1/downstream_ws
  rm -rf "$down"
  mkdir -p "$down/src"
  ln -sfn "$2/test/downstream" "$down/src/mbk_downstream"
  cd "$down" && catkin_make -DPYTHON_EXECUTABLE=/usr/bin/python3
  "$down/devel/lib/mbk_downstream/mbk_downstream"
' _ "$ws" "$src" >>"$log" 2>&1 || fail "from install/setup.bash"
echo "install test: catkin_lint clean, install space runs mbk, rosmsg, the Python module and a" \
  "downstream package" \
  "(built in the same workspace, and on top of the install space)"
