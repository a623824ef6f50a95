#!/usr/bin/env python3
"""The launch files one after another on one ROS master, as a user starts them (ctest
relaunch; test/ros.cmake): each start sets the node's parameters from its own arguments alone.

1. mb_kinematics.launch on the ten-body scene with publish_tf:=false: the start-up line says
   that /tf is not published.
2. demo.launch on the same scene (demo_publisher's ~model).
3. demo.launch with its defaults (the human body URDF, /tf on): the node loads the URDF's bodies
   (not the scene a previous start left in ~model), its start-up line says the frames go on /tf,
   and /tf carries every moving body's frame (a previous start's ~outputs without tf does not
   linger), while demo_publisher drives them (not with the scene's coordinates).

Usage: relaunch_test.py   (in a sourced catkin workspace)
"""
import os
import re
import signal
import socket
import subprocess
import sys
import tempfile
import threading
import time
import xml.etree.ElementTree as ET

STARTED = re.compile(r"mb_kinematics: (\d+) bodies, .*coordinates, max depth.*")


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class Launch:
    """roslaunch ARGS in the background, its output kept; stop() ends it with SIGINT."""

    def __init__(self, args, env, log):
        self.log_path = log
        self.log = open(log, "w")
        self.proc = subprocess.Popen(["stdbuf", "-oL", "roslaunch"] + args, env=env, stdout=self.log,
                                     stderr=subprocess.STDOUT, start_new_session=True)

    def started_line(self, seconds):
        """The node's start-up line, once it is out (None after `seconds`)."""
        end = time.time() + seconds
        while time.time() < end:
            m = STARTED.search(open(self.log_path).read())
            if m:
                return m
            if self.proc.poll() is not None:
                return None
            time.sleep(0.1)
        return None

    def stop(self):
        """As Ctrl-C: roslaunch stops its nodes (SIGINT, SIGTERM 15 s later) and ends."""
        if self.proc.poll() is None:
            os.killpg(self.proc.pid, signal.SIGINT)
            try:
                self.proc.wait(timeout=60)
            except subprocess.TimeoutExpired:
                os.killpg(self.proc.pid, signal.SIGKILL)
                self.proc.wait()
        self.log.close()


def moving_bodies(urdf):
    """The child links of the URDF's non-fixed joints: the frames the node puts on /tf."""
    root = ET.parse(urdf).getroot()
    return {j.find("child").get("link") for j in root.findall("joint") if j.get("type") != "fixed"}


def tf_frames_within(seconds, wanted):
    """The child frames seen on /tf (rospy, this process), until all of `wanted` or `seconds`."""
    import rospy
    from tf2_msgs.msg import TFMessage
    seen, lock = set(), threading.Lock()

    def on_tf(msg):
        with lock:
            seen.update(t.child_frame_id for t in msg.transforms)

    sub = rospy.Subscriber("/tf", TFMessage, on_tf)
    end = time.time() + seconds
    while time.time() < end:
        with lock:
            if wanted <= seen:
                break
        time.sleep(0.1)
    sub.unregister()
    with lock:
        return set(seen)


def check(problems, condition, text):
    if not condition:
        problems.append(text)
        print("FAIL: " + text, file=sys.stderr)


def main():
    share = subprocess.check_output(["rospack", "find", "mb_kinematics"], text=True).strip()
    scene = os.path.join(share, "config", "ten_body.yaml")
    urdf = os.path.join(share, "config", "human_body.urdf")
    bodies = ET.parse(urdf).getroot().findall("link")
    tmp = tempfile.mkdtemp(prefix="mbk_relaunch_")
    port = free_port()
    env = dict(os.environ, ROS_MASTER_URI="http://127.0.0.1:%d" % port, ROS_HOSTNAME="127.0.0.1",
               ROS_HOME=tmp, PYTHONUNBUFFERED="1")  # roslaunch's output as it comes
    os.environ.update(env)
    master = subprocess.Popen(["roscore", "-p", str(port)], env=env, stdout=subprocess.DEVNULL,
                              stderr=subprocess.DEVNULL, start_new_session=True)
    problems = []
    try:
        for _ in range(100):  # the master up, its run_id set (roslaunch compares its own)
            if subprocess.call(["rosparam", "get", "/run_id"], env=env, stdout=subprocess.DEVNULL,
                               stderr=subprocess.DEVNULL) == 0:
                break
            time.sleep(0.2)
        first = Launch(["mb_kinematics", "mb_kinematics.launch", "model:=" + scene,
                        "publish_tf:=false"], env, os.path.join(tmp, "first.log"))
        line = first.started_line(60)
        first.stop()
        check(problems, line is not None, "mb_kinematics.launch publish_tf:=false did not start")
        if line:
            print("start 1: " + line.group(0))
            check(problems, "no /tf" in line.group(0) and "publish_tf:=false" in line.group(0),
                  "the start-up line with publish_tf:=false does not say that /tf is off")

        second = Launch(["mb_kinematics", "demo.launch", "model:=" + scene], env,
                        os.path.join(tmp, "second.log"))
        line = second.started_line(60)
        second.stop()
        check(problems, line is not None, "demo.launch on the scene did not start")

        third = Launch(["mb_kinematics", "demo.launch"], env, os.path.join(tmp, "third.log"))
        line = third.started_line(60)
        try:
            check(problems, line is not None, "demo.launch did not start")
            if line:
                print("start 3: " + line.group(0))
                check(problems, int(line.group(1)) == len(bodies) - 1,
                      "demo.launch's node loaded %s bodies, the URDF has %d (a previous start's "
                      "~model lingers?)" % (line.group(1), len(bodies) - 1))
                check(problems, "frames on /tf" in line.group(0),
                      "the start-up line does not say that the frames go on /tf")
                import rospy
                rospy.init_node("relaunch_test", anonymous=True, disable_signals=True)
                wanted = moving_bodies(urdf)
                seen = tf_frames_within(30, wanted)
                check(problems, wanted <= seen,
                      "/tf lacks %d of the %d moving bodies' frames (a previous start's ~outputs "
                      "lingers, or demo_publisher drives another model): e.g. %s" %
                      (len(wanted - seen), len(wanted), sorted(wanted - seen)[:3]))
        finally:
            third.stop()
    finally:
        os.killpg(master.pid, signal.SIGINT)
        master.wait()
    if problems:
        for name in ("first", "second", "third"):
            print("--- %s.log (tail)" % name, file=sys.stderr)
            print("".join(open(os.path.join(tmp, name + ".log")).readlines()[-15:]),
                  file=sys.stderr)
    print("relaunch: %s" % ("FAILED" if problems else "ok"))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
