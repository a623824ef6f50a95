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

MBK_PACKAGES=(
  build-essential cmake catkin libroscpp-dev libtf2-ros-dev ros-sensor-msgs ros-geometry-msgs
  ros-std-msgs ros-visualization-msgs ros-message-generation ros-message-runtime liburdf-dev
  liburdfdom-dev libtinyxml2-dev libeigen3-dev libyaml-cpp-dev python3-rostest
  python3-roslaunch python3-rostopic python3-rosmsg rosbash ros-robot-state-publisher
  libkdl-parser-dev liborocos-kdl-dev libbenchmark-dev googletest libboost-dev
  libdiagnostic-updater-dev libsensor-msgs-dev python3-sensor-msgs python3-geometry-msgs
  python3-tf2-msgs python3-diagnostic-msgs
  librviz-dev rviz qtbase5-dev libvisualization-msgs-dev xvfb xauth imagemagick
  pluginlib-dev libogre-1.12-dev librosbag-dev libtf2-msgs-dev libnav-msgs-dev python3-rosbag
  libstd-srvs-dev python3-std-srvs tf2-tools  # tf2-tools: static_transform_publisher
  python3-matplotlib catkin-lint
  joint-state-publisher-gui  # mb_kinematics.launch gui:=true
  libnodelet-dev libnodeletlib-dev libnodeletlib-tools libtopic-tools-dev  # the nodelet; load_monitor
  clang-14 libclang-rt-14-dev  # scripts/fuzz.sh: libFuzzer, ASan, UBSan
  valgrind  # the loaders' memcheck (test/tests.cmake)
  libdart-dev libdart-utils-urdf-dev  # kinematics_benchmark's DART peer only (bench/bench.cmake)
  pybind11-dev python3-pybind11 python3-dev python3-numpy  # the Python module (doc/python.md)
  python3-pytest python3-pykdl python3-dartpy  # its tests and their peers
)

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

mbk_build() {
  mkdir -p "$MBK_WS/src"
  ln -sfn "$MBK_SRC" "$MBK_WS/src/mb_kinematics"
  echo "== building in $MBK_WS"
  (cd "$MBK_WS" && catkin_make -j2 -DCMAKE_BUILD_TYPE=Release -DPYTHON_EXECUTABLE=/usr/bin/python3 \
     -DCATKIN_ENABLE_TESTING=ON "$@" >"$MBK_WS/build.log" 2>&1) || {
    tail -n 60 "$MBK_WS/build.log"
    echo "build failed: full log in $MBK_WS/build.log" >&2
    return 1
  }
  set +u
  # shellcheck disable=SC1091
  source "$MBK_WS/devel/setup.bash"
  set -u
}
