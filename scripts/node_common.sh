# shellcheck shell=bash
# Sourced (not run) by scripts/node_load.sh and scripts/node_instructions.sh: the workspace's
# environment on a ROS master of one's own, and the random tree both load.

# node_script_env NAME PORT: MBK_ROOT, MBK_WS (its build checked), ROS on 127.0.0.1:PORT, BIN
# (the devel space's executables), TMP (a new folder /tmp/mbk_NAME.XXXXXX) and PIDS (empty).
node_script_env() {
  MBK_ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
  MBK_WS=${MBK_WS:-${XDG_CACHE_HOME:-$HOME/.cache}/mb_kinematics/ws-$(echo "$MBK_ROOT" | md5sum | cut -c1-8)}
  [ -f "$MBK_WS/devel/setup.bash" ] || { echo "$1.sh: no build in $MBK_WS (run scripts/test.sh)" >&2; exit 1; }
  export PATH=/usr/bin:$PATH PYTHONNOUSERSITE=1
  set +u
  # shellcheck disable=SC1091
  source "$MBK_WS/devel/setup.bash"
  set -u
  export ROS_MASTER_URI=http://127.0.0.1:$2 ROS_IP=127.0.0.1
  unset ROS_HOSTNAME
  # shellcheck disable=SC2034  # BIN: for the scripts that source this
  BIN=$MBK_WS/devel/lib/mb_kinematics
  TMP=$(mktemp -d "/tmp/mbk_$1.XXXXXX")
  PIDS=()
}

# start_master PORT URDF: roscore -p PORT (its pid added to PIDS), URDF as /robot_description.
start_master() {
  roscore -p "$1" >"$TMP/roscore.log" 2>&1 &
  PIDS+=($!)
  for _ in $(seq 100); do rosparam get /rosdistro >/dev/null 2>&1 && break; sleep 0.2; done
  rosparam set --textfile "$2" /robot_description
}

# A random tree of N links: link k's parent is one of links 0..k-1, joint axes x, y or z.
random_tree_urdf() {
  awk -v n="$1" 'BEGIN {
    srand(1); print "<?xml version=\"1.0\"?>\n<robot name=\"tree" n "\">";
    for (k = 0; k < n; k++) {
      printf "  <link name=\"l%d\"><inertial><origin xyz=\"0 0 0.05\"/><mass value=\"1\"/>", k;
      print "<inertia ixx=\"0.01\" iyy=\"0.01\" izz=\"0.01\" ixy=\"0\" ixz=\"0\" iyz=\"0\"/></inertial></link>";
      if (k == 0) continue;
      p = int(rand() * k); a = int(rand() * 3);
      printf "  <joint name=\"j%d\" type=\"continuous\"><parent link=\"l%d\"/><child link=\"l%d\"/>", k, p, k;
      printf "<origin xyz=\"%.3f %.3f %.3f\"/><axis xyz=\"%d %d %d\"/></joint>\n", rand() * 0.2,
        rand() * 0.2, 0.1, a == 0, a == 1, a == 2;
    }
    print "</robot>" }'
}
