#!/usr/bin/env python3
"""The node beside robot_state_publisher (tf_duplicate.test).

publish_tf true: after ~reload (which watches /tf again, as at start) the node warns once, in
one line, naming /robot_state_publisher, a frame and publish_tf:=false.
publish_tf false: robot_state_publisher's frames reach /tf and none from the node, while
body_kinematics still flows; no warning after ~reload.
"""
import threading
import time
import unittest

import rospy
import rostest
from mb_kinematics_msgs.msg import BodyKinematicsArray
from rosgraph_msgs.msg import Log
from std_srvs.srv import Trigger
from tf2_msgs.msg import TFMessage

NODE = "/mb_kinematics"
RSP = "/robot_state_publisher"


class TfDuplicateTest(unittest.TestCase):
    def setUp(self):
        self.lock = threading.RLock()
        self.warnings = []  # (receive time, text) of the node's WARN lines
        self.tf_frames = {}  # publisher -> child frames seen on /tf
        self.kinematics = 0
        self.subs = [
            rospy.Subscriber("/rosout", Log, self.on_log),
            rospy.Subscriber("/tf", TFMessage, self.on_tf),
            rospy.Subscriber("body_kinematics", BodyKinematicsArray, self.on_kinematics),
        ]

    def tearDown(self):
        for s in self.subs:
            s.unregister()

    def on_log(self, msg):
        if msg.name == NODE and msg.level == Log.WARN:
            with self.lock:
                self.warnings.append((time.time(), msg.msg))

    def on_tf(self, msg):
        caller = msg._connection_header["callerid"]
        with self.lock:
            self.tf_frames.setdefault(caller, set()).update(t.child_frame_id for t in msg.transforms)

    def on_kinematics(self, _):
        with self.lock:
            self.kinematics += 1

    def wait_for(self, condition, seconds):
        end = time.time() + seconds
        while time.time() < end:
            with self.lock:
                if condition():
                    return True
            time.sleep(0.05)
        return False

    def warnings_since(self, t0):
        with self.lock:
            return [text for t, text in self.warnings if t >= t0]

    def reload(self):
        rospy.wait_for_service(NODE + "/reload", 20)
        self.assertTrue(rospy.ServiceProxy(NODE + "/reload", Trigger)().success)

    def test_beside_robot_state_publisher(self):
        self.assertTrue(self.wait_for(lambda: self.kinematics > 10 and RSP in self.tf_frames, 20),
                        "no body_kinematics from the node or no /tf from robot_state_publisher")
        time.sleep(1.0)  # the /rosout connections up
        t0 = time.time()
        self.reload()
        if rospy.get_param("~publish_tf"):
            self.assertTrue(self.wait_for(lambda: self.warnings_since(t0), 10), "no warning")
            time.sleep(2.0)
            lines = self.warnings_since(t0)
            self.assertEqual(len(lines), 1, lines)
            line = lines[0]
            self.assertNotIn("\n", line)
            self.assertIn(RSP, line)
            self.assertIn("publish_tf:=false", line)
            with self.lock:
                ours = self.tf_frames.get(NODE, set())
            self.assertTrue(any("'%s'" % f in line for f in ours), (line, ours))
        else:
            time.sleep(3.0)
            self.assertEqual(self.warnings_since(t0), [])
            with self.lock:
                self.assertNotIn(NODE, self.tf_frames)
                self.assertTrue(self.tf_frames[RSP])
                self.assertGreater(self.kinematics, 50)


if __name__ == "__main__":
    rospy.init_node("tf_duplicate_test")
    rostest.rosrun("mb_kinematics", "tf_duplicate_test", TfDuplicateTest)
