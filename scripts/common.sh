# Shared by scripts/demo.sh and scripts/test.sh: install what is missing, set up the catkin
# workspace and build. Sourced, not run. The workspace (MBK_WS) is outside the git tree, by
# default one per checkout under ~/.cache/mb_kinematics/ (inside the tree, its src/ link back
# to the repo would make a loop that rosrun's search runs into).
set -euo pipefail

MBK_SRC=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
MBK_WS=${MBK_WS:-${XDG_CACHE_HOME:-$HOME/.cache}/mb_kinematics/ws-$(echo "$MBK_SRC" | md5sum | cut -c1-8)}
# catkin needs Debian's python3 (with catkin_pkg), not a pyenv build earlier on PATH.
export PATH=/usr/bin:$PATH
export PYTHONNOUSERSITE=1

# What scripts/demo.sh needs: the packages' build dependencies (every find_package of the
# CMakeLists, so that the workspace configures) and what the demo and the README's quick start
# run (roslaunch, rosrun, rostopic, the Python module with numpy). Nothing that only the tests,
# benchmarks, fuzzers or an optional launch argument use.
MBK_DEMO_PACKAGES=(
  build-essential cmake catkin libroscpp-dev libtf2-ros-dev ros-sensor-msgs ros-geometry-msgs
  ros-std-msgs ros-visualization-msgs ros-message-generation ros-message-runtime liburdf-dev
  liburdfdom-dev libtinyxml2-dev libeigen3-dev libyaml-cpp-dev libboost-dev
  libdiagnostic-updater-dev libsensor-msgs-dev libvisualization-msgs-dev librosbag-dev
  libtf2-msgs-dev libnav-msgs-dev libstd-srvs-dev libnodelet-dev libnodeletlib-dev
  libtopic-tools-dev pluginlib-dev
  pybind11-dev python3-dev python3-numpy  # the Python module (doc/python.md)
  libmujoco-dev libsdformat-dev  # MJCF and SDFormat models (doc/conventions.md)
  libhdf5-dev  # mbk bag --h5 (doc/recorded_data.md)
  libbz2-dev libroslz4-dev  # a bag's chunks checked before librosbag reads them
  python3-roslaunch rosbash python3-rostopic python3-sensor-msgs python3-geometry-msgs
  python3-rosservice  # the docs' rosservice call ~reload, ~get_partial_velocities
)
# rviz and what the display plugin builds against: scripts/demo.sh --rviz, and the tests.
MBK_RVIZ_PACKAGES=(librviz-dev rviz qtbase5-dev libogre-1.12-dev)
# What scripts/test.sh needs on top: the test frameworks, the peers the tests and benchmarks
# compare with, and the tools the tests run.
MBK_TEST_PACKAGES=(
  "${MBK_RVIZ_PACKAGES[@]}" xvfb xauth imagemagick  # the rviz screenshot tests
  googletest python3-rostest libbenchmark-dev python3-rosmsg python3-rosbag python3-std-srvs
  python3-tf2-msgs python3-diagnostic-msgs
  ros-robot-state-publisher libkdl-parser-dev liborocos-kdl-dev  # the peers of the node tests
  tf2-tools  # static_transform_publisher (launch/two_robots.launch)
  python3-matplotlib catkin-lint
  libnodeletlib-tools  # the nodelet manager (the nodelet's tests; load_monitor)
  clang-14 libclang-rt-14-dev  # scripts/fuzz.sh: libFuzzer, ASan, UBSan
  llvm-14  # llvm-symbolizer: a fuzz finding's stack with function names
  valgrind  # the loaders' memcheck (test/tests.cmake)
  libdart-dev libdart-utils-urdf-dev  # kinematics_benchmark's DART peer only (bench/bench.cmake)
  python3-pytest python3-pykdl python3-dartpy  # the Python module's tests and their peers
  python3-scipy  # the Butterworth estimator's peer (test/python/test_butterworth.py)
  python3-mypy  # the Python stubs checked against the module (test/python/test_typing.py)
  python3-dask python3-distributed python3-psutil  # mbk batch --scheduler's tests (Dask)
  python3-nav-msgs  # the Python tests write base odometry (test/python/test_recordings.py)
  python3-h5py  # mbk bag --h5's files read back (test/python/test_h5_output.py)
  joint-state-publisher-gui  # mb_kinematics.launch gui:=true (Qt: 106 packages; gui_launch)
)
# What mbk_install_deps installs: scripts/test.sh adds MBK_TEST_PACKAGES.
MBK_PACKAGES=("${MBK_DEMO_PACKAGES[@]}")

mbk_install_deps() {
  local missing=()
  for p in "${MBK_PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  echo "== installing: ${missing[*]}"
  local sudo=""
  [ "$(id -u)" -eq 0 ] || sudo=sudo
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
}

# mbk_build [-DCMAKE_OPTION=...] [TARGET...]: catkin_make in MBK_WS; with targets, only those
# and what they need. A workspace configured here for the first time has its tests off
# (CATKIN_ENABLE_TESTING=OFF: its configure needs no test package) unless the options say
# otherwise; a workspace configured before keeps its setting. Either way the same compiler
# flags: scripts/test.sh after scripts/demo.sh recompiles nothing the demo built.
mbk_build() {
  mkdir -p "$MBK_WS/src"
  ln -sfn "$MBK_SRC" "$MBK_WS/src/mb_kinematics"
  local testing=()
  [ -f "$MBK_WS/build/CMakeCache.txt" ] || testing=(-DCATKIN_ENABLE_TESTING=OFF)
  echo "== building in $MBK_WS${1:+: $*}"
  (cd "$MBK_WS" && catkin_make -j2 -DCMAKE_BUILD_TYPE=Release -DPYTHON_EXECUTABLE=/usr/bin/python3 \
     "${testing[@]}" "$@" >"$MBK_WS/build.log" 2>&1) || {
    tail -n 60 "$MBK_WS/build.log"
    echo "build failed: full log in $MBK_WS/build.log" >&2
    return 1
  }
  set +u
  # shellcheck disable=SC1091
  source "$MBK_WS/devel/setup.bash"
  set -u
}
