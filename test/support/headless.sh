# Sourced by the headless script tests (test/rviz/screenshot_test.sh, test/ros/gui_launch_test.sh)
# after they define fail(): a temporary folder $tmp (ROS_HOME and HOME inside it); the processes
# they start, in pids, stopped newest first on exit (SIGINT, then SIGKILL after 5 s), then
# keep_logs if the script defines it, then $tmp removed; start_xvfb (an Xvfb screen of its own,
# DISPLAY set) and free_port.
tmp=$(mktemp -d "${TMPDIR:-/tmp}/mbk_headless_test.XXXXXX")
export ROS_HOME=$tmp/ros HOME=$tmp/home
mkdir -p "$HOME"
pids=()

stop() {
  local i p
  for ((i = ${#pids[@]} - 1; i >= 0; i--)); do
    p=${pids[i]}
    kill -INT "$p" 2>/dev/null || continue
    for _ in $(seq 50); do kill -0 "$p" 2>/dev/null || break; sleep 0.1; done
    kill -KILL "$p" 2>/dev/null
    wait "$p" 2>/dev/null
  done
  if declare -F keep_logs >/dev/null; then keep_logs; fi
  rm -rf "$tmp"
}
trap stop EXIT
trap 'exit 130' INT TERM

# Xvfb picks a free display number and writes it to fd 3.
start_xvfb() {
  Xvfb -displayfd 3 -screen 0 1280x900x24 -nolisten tcp 3>"$tmp/display" >"$tmp/xvfb.log" 2>&1 &
  pids+=($!)
  for _ in $(seq 100); do [ -s "$tmp/display" ] && break; sleep 0.1; done
  [ -s "$tmp/display" ] || fail "Xvfb did not start: $(cat "$tmp/xvfb.log")"
  export DISPLAY=:$(head -n1 "$tmp/display")
}

free_port() {
  python3 -c 'import socket; s = socket.socket(); s.bind(("", 0)); print(s.getsockname()[1])'
}
