#!/usr/bin/env python3
"""A robot's xacro source given where a URDF is expected (ctest xacro_launch; test/ros.cmake):
both refusals name xacro and the command that expands it.

1. mb_kinematics.launch model:=arm.urdf.xacro stops before it starts anything, its one message
   naming `xacro arm.urdf.xacro > robot.urdf` (not the `mbk urdf --display` it would have run).
2. The same xacro text as robot_description (loaded with textfile= instead of through xacro):
   the node's fatal line names xacro, the markup and the command (not urdfdom's "No link elements
   found").

Usage: xacro_launch_test.py   (in a sourced catkin workspace)
"""
import os
import signal
import socket
import subprocess
import sys
import tempfile
import time

XACRO = """<?xml version="1.0"?>
<robot name="arm" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="segment" params="name">
    <link name="${name}"/>
  </xacro:macro>
  <link name="base"/>
  <xacro:segment name="upper"/>
</robot>
"""


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def run(args, env, seconds=60):
    p = subprocess.run(args, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                       timeout=seconds)
    return p.returncode, p.stdout


def expect(problems, condition, text, output):
    if not condition:
        problems.append(text)
        print("FAIL: %s; output:\n%s" % (text, output), file=sys.stderr)


def main():
    tmp = tempfile.mkdtemp(prefix="mbk_xacro_")
    xacro = os.path.join(tmp, "arm.urdf.xacro")
    with open(xacro, "w") as f:
        f.write(XACRO)
    port = free_port()
    env = dict(os.environ, ROS_MASTER_URI="http://127.0.0.1:%d" % port, ROS_HOSTNAME="127.0.0.1",
               ROS_HOME=tmp)
    problems = []

    rc, out = run(["roslaunch", "mb_kinematics", "mb_kinematics.launch", "model:=" + xacro], env)
    print("model:=arm.urdf.xacro: exit %d" % rc)
    expect(problems, rc != 0, "roslaunch did not refuse the xacro model", out)
    expect(problems, "model:=%s is a xacro file: expand it first: xacro %s > robot.urdf" %
           (xacro, xacro) in out, "the refusal does not name xacro and its command", out)
    expect(problems, "mbk urdf" not in out, "the refusal names mbk urdf", out)

    master = subprocess.Popen(["roscore", "-p", str(port)], env=env, stdout=subprocess.DEVNULL,
                              stderr=subprocess.DEVNULL, start_new_session=True)
    try:
        for _ in range(100):
            if run(["rosparam", "set", "-t", xacro, "robot_description"], env)[0] == 0:
                break
            time.sleep(0.2)
        rc, out = run(["roslaunch", "mb_kinematics", "mb_kinematics.launch"], env)
        print("robot_description from the xacro text: exit %d" % rc)
        expect(problems, "robot_description: a xacro document, not a URDF (<xacro:macro> at "
               "line 3): expand it first: xacro ROBOT.urdf.xacro > robot.urdf" in out,
               "the node's refusal does not name xacro, the markup and the command", out)
        expect(problems, 'command="xacro ROBOT.urdf.xacro"' in out,
               "the node's refusal does not say how a launch file loads it through xacro", out)
        expect(problems, "No link elements" not in out, "urdfdom's message reached the user", out)
    finally:
        os.killpg(master.pid, signal.SIGINT)
        master.wait()
    print("xacro_launch: %s" % ("FAILED" if problems else "ok"))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
