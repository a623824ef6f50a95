#!/usr/bin/env bash
# The rviz display on the demo, headless: its own ROS master (a free port), demo.launch on the
# human body model, rviz with config/mb_kinematics.rviz (or LAUNCH, DEMO_ARGS and RVIZ_CONFIG:
# bvh.launch and config/bvh.rviz on the real walk) on an Xvfb screen of its own; screenshots
# (`import -window root`) until each arrow color of the display shows on more than MIN_PIXELS
# pixels (up to TIMEOUT s). Fails if the plugin does not load, rviz reports a plugin or display
# error, or nothing is drawn. Keeps the last screenshot and rviz's output in OUT_DIR.
#   test/rviz/screenshot_test.sh OUT_DIR    (in a sourced catkin workspace: devel/env.sh ...)
# On another robot (test/rviz.cmake): DEMO_ARGS=model:=ROBOT.urdf; EXPECT_FRAME=LINK: the display
# must have set the Fixed Frame (config/mb_kinematics.rviz says `world`) to LINK; REGION=X0,Y0,X1,Y1:
# only pixels there count (the middle of the 3D view, where the framed robot is); CENTER=X,Y,TOL:
# the centroid of the arrows' pixels must be within TOL pixels of X,Y in each direction (the
# camera frames the robot); SHOT_NAME: the name of the kept files; SETTLE=S: screenshots count
# only after S s of motion (the camera must keep the moving robot in view; TIMEOUT counts on);
# EXPECT_FOLLOW=FRAME: the display must have made the view follow FRAME; ARROW_FRACTION=LO,HI: over
# SHOTS (default 12) more screenshots 1 s apart, the longest velocity and acceleration arrows must
# be LO to HI of the robot's size on screen (test/rviz/arrow_lengths.py, in the 3D view: the 75th
# percentile over the screenshots).
# Hostile runs (LAUNCH=hostile_bodies.launch, test/rviz.cmake): READY: the launch's line that says
# it is up (default: the node's "coordinates, max depth"); MAX_RSS_MB: rviz may hold at most this
# resident memory at the end; SIGINT_WITHIN=S: rviz must exit within S s of a SIGINT; HOLD=S:
# rviz must still be running S s after the arrows showed.
set -uo pipefail
out_dir=${1:?usage: screenshot_test.sh OUT_DIR}
src=$(cd "$(dirname "$0")/../.." && pwd)
MIN_PIXELS=${MIN_PIXELS:-50}
TIMEOUT=${TIMEOUT:-60}
SHOT_NAME=${SHOT_NAME:-rviz_screenshot}
EXPECT_FRAME=${EXPECT_FRAME:-}
REGION=${REGION:-}
CENTER=${CENTER:-}
READY=${READY:-coordinates, max depth}
MAX_RSS_MB=${MAX_RSS_MB:-}
SIGINT_WITHIN=${SIGINT_WITHIN:-}
HOLD=${HOLD:-0}
SETTLE=${SETTLE:-0}
mkdir -p "$out_dir"
fail() { echo "FAIL: $*" >&2; exit 1; }
keep_logs() { cp "$tmp/rviz.log" "$out_dir/${SHOT_NAME}_rviz.log" 2>/dev/null; }
# shellcheck source=../support/headless.sh
source "$src/test/support/headless.sh"
start_xvfb

port=$(free_port)
export ROS_MASTER_URI=http://localhost:$port
stdbuf -oL roslaunch -p "$port" mb_kinematics ${LAUNCH:-demo.launch} ${DEMO_ARGS:-} >"$tmp/launch.log" 2>&1 &
pids+=($!)
for _ in $(seq 300); do grep -q "$READY" "$tmp/launch.log" && break; sleep 0.1; done
grep -q "$READY" "$tmp/launch.log" || fail "${LAUNCH:-demo.launch} did not start: $(tail "$tmp/launch.log")"

stdbuf -oL rviz -d "${RVIZ_CONFIG:-$src/config/mb_kinematics.rviz}" >"$tmp/rviz.log" 2>&1 &
rviz_pid=$!
pids+=($rviz_pid)

passed=false
start=$SECONDS
while [ $((SECONDS - start)) -lt "$TIMEOUT" ]; do
  sleep 1
  kill -0 "$rviz_pid" 2>/dev/null || fail "rviz exited: $(tail -n 20 "$tmp/rviz.log")"
  [ $((SECONDS - start)) -lt "$SETTLE" ] && continue
  import -window root "$tmp/shot.png" 2>/dev/null || continue
  python3 "$src/test/rviz/count_colors.py" "$tmp/shot.png" ${REGION:+--region "$REGION"} \
    >"$tmp/counts" || continue
  cp "$tmp/shot.png" "$out_dir/$SHOT_NAME.png"
  if awk -v min="$MIN_PIXELS" -v center="$CENTER" '
      $1 != "centroid" && $2 <= min { bad = 1 }
      $1 == "centroid" && center != "" {
        split(center, c, ",")
        if ($2 < c[1] - c[3] || $2 > c[1] + c[3] || $3 < c[2] - c[3] || $3 > c[2] + c[3]) bad = 1
      }
      END { exit bad }' "$tmp/counts"; then
    passed=true
    break
  fi
done
echo "pixels per arrow color${REGION:+ in $REGION} after $((SECONDS - start)) s (more than $MIN_PIXELS needed):"
sed 's/^/  /' "$tmp/counts" 2>/dev/null
echo "screenshot: $out_dir/$SHOT_NAME.png"

# Plugin or display errors (Debian's rviz always logs the harmless media_export one).
errors=$(grep -iE 'error|failed|exception' "$tmp/rviz.log" | grep -v -e 'no such package media_export' -e '\[librospack\]: error while executing command')
[ -z "$errors" ] || fail "rviz reported errors:
$errors"
if [ -n "$EXPECT_FRAME" ]; then
  grep -q "set to '$EXPECT_FRAME', the frame of the body kinematics" "$tmp/rviz.log" ||
    fail "the display did not set the Fixed Frame to '$EXPECT_FRAME'"
elif grep -q "is not in tf; set to" "$tmp/rviz.log"; then
  fail "the display changed the config's Fixed Frame, which tf knows"
fi
if [ -n "${EXPECT_FOLLOW:-}" ]; then
  grep -q "the view follows '$EXPECT_FOLLOW'" "$tmp/rviz.log" ||
    fail "the display did not make the view follow '$EXPECT_FOLLOW'"
fi
$passed || fail "the display's arrow colors did not show${REGION:+ in $REGION}${CENTER:+ centred on $CENTER} within $TIMEOUT s${SETTLE:+ (from $SETTLE s on)}"
if [ -n "${ARROW_FRACTION:-}" ]; then
  shots=()
  for i in $(seq "${SHOTS:-12}"); do
    sleep 1
    import -window root "$tmp/arrows_$i.png" 2>/dev/null && shots+=("$tmp/arrows_$i.png")
  done
  [ ${#shots[@]} -gt 0 ] || fail "no screenshot for the arrow lengths"
  /usr/bin/python3 "$src/test/rviz/arrow_lengths.py" "${shots[@]}" --region 364,62,1264,802 \
    --check "$ARROW_FRACTION" >"$tmp/arrows"
  fits=$?
  cp "${shots[-1]}" "$out_dir/${SHOT_NAME}_arrows.png"
  echo "longest arrow per color over ${#shots[@]} screenshots (px; fraction of the robot's size on screen):"
  sed 's/^/  /' "$tmp/arrows"
  [ "$fits" = 0 ] || fail "the longest velocity or acceleration arrow is not $ARROW_FRACTION of the robot's size on screen"
fi
# rviz's CPU time (user + system, clock ticks) and the wall time, for its CPU % over HOLD.
cpu_ticks() { awk '{ print $14 + $15 }' "/proc/$rviz_pid/stat"; }
if [ "$HOLD" -gt 0 ]; then
  ticks=$(cpu_ticks)
  held=$(date +%s.%N)
  sleep "$HOLD"
  kill -0 "$rviz_pid" 2>/dev/null || fail "rviz exited after drawing: $(tail -n 20 "$tmp/rviz.log")"
  cpu=$(awk -v t0="$ticks" -v t1="$(cpu_ticks)" -v w0="$held" -v w1="$(date +%s.%N)" \
    -v hz="$(getconf CLK_TCK)" 'BEGIN { printf "%.0f", 100 * (t1 - t0) / hz / (w1 - w0) }')
  echo "rviz still running $HOLD s later, ${cpu}% CPU over them (load $(cut -d' ' -f1 /proc/loadavg))"
fi
if [ -n "$MAX_RSS_MB" ]; then
  rss_mb=$(awk '/^VmRSS:/ { print int($2 / 1024) }' "/proc/$rviz_pid/status")
  echo "rviz holds $rss_mb MB (at most $MAX_RSS_MB allowed)"
  [ "$rss_mb" -le "$MAX_RSS_MB" ] || fail "rviz holds $rss_mb MB, more than $MAX_RSS_MB MB"
fi
if [ -n "$SIGINT_WITHIN" ]; then
  kill -INT "$rviz_pid"
  sent=$(date +%s.%N)
  since() { awk -v a="$sent" -v b="$(date +%s.%N)" 'BEGIN { printf "%.2f", b - a }'; }
  while kill -0 "$rviz_pid" 2>/dev/null &&
    awk -v t="$(since)" -v s="$SIGINT_WITHIN" 'BEGIN { exit !(t < s) }'; do sleep 0.05; done
  kill -0 "$rviz_pid" 2>/dev/null && fail "rviz did not exit within $SIGINT_WITHIN s of SIGINT"
  echo "rviz exited $(since) s after SIGINT (at most $SIGINT_WITHIN s allowed)"
fi
echo "PASS"
