#!/usr/bin/python3
"""Publishes mb_kinematics_msgs/BodyKinematicsArray on body_kinematics for the rviz display's
hostile runs (test/rviz.cmake): ~bodies bodies (default 40) in a 1 m ring around (~x, ~y, 0)
of frame `odom` (default: UTM coordinates, x 500000, y 5000000, as a GPS-localised robot's
odometry gives), every quantity non-zero; the first body's name ~name_length characters long
(default 30,000); ~rate messages per second, ~count of them (default 0: no end). A static transform world -> odom of (-x, -y, 0)
puts config/mb_kinematics.rviz's Fixed Frame `world` at the robot, as a user's map frame near the
robot does (rviz draws in float: near the camera, as its own displays do). Prints "hostile
bodies: publishing" once the first message is out."""
import math

import rospy
import tf2_ros
from geometry_msgs.msg import TransformStamped
from mb_kinematics_msgs.msg import BodyKinematics, BodyKinematicsArray


def body(k, n, x0, y0, name):
    b = BodyKinematics()
    b.name, b.index, b.lower_body = name, k + 1, k
    angle = 2 * math.pi * k / n
    b.pose.position.x = x0 + 0.5 * math.cos(angle)
    b.pose.position.y = y0 + 0.5 * math.sin(angle)
    b.pose.position.z = 0.5
    b.pose.orientation.w = 1
    b.mass_center.x, b.mass_center.y = b.pose.position.x, b.pose.position.y
    b.mass_center.z = 0.6
    b.twist.linear.x, b.twist.linear.y = -math.sin(angle), math.cos(angle)
    b.accel.linear.x, b.accel.linear.y = -math.cos(angle), -math.sin(angle)
    b.twist.angular.z = 1 + 0.1 * k
    b.accel.angular.x = 1
    return b


def main():
    rospy.init_node("hostile_bodies")
    n = rospy.get_param("~bodies", 40)
    x0, y0 = rospy.get_param("~x", 500000.0), rospy.get_param("~y", 5000000.0)
    name_length = rospy.get_param("~name_length", 30000)
    rate = rospy.Rate(rospy.get_param("~rate", 10.0))
    static = tf2_ros.StaticTransformBroadcaster()
    t = TransformStamped()
    t.header.stamp = rospy.Time.now()
    t.header.frame_id, t.child_frame_id = "world", "odom"
    t.transform.translation.x, t.transform.translation.y = -x0, -y0
    t.transform.rotation.w = 1
    static.sendTransform(t)
    pub = rospy.Publisher("body_kinematics", BodyKinematicsArray, queue_size=2)
    msg = BodyKinematicsArray()
    msg.header.frame_id = "odom"
    long_name = ("long" + "n" * name_length)[:name_length]
    msg.bodies = [body(k, n, x0, y0, long_name if k == 0 else "body%d" % k) for k in range(n)]
    announced = False
    count = rospy.get_param("~count", 0)
    sent = 0
    while not rospy.is_shutdown():
        if count and sent == count:
            rate.sleep()
            continue
        sent += 1
        msg.header.stamp = rospy.Time.now()
        pub.publish(msg)
        if not announced:
            print("hostile bodies: publishing", flush=True)
            announced = True
        rate.sleep()


if __name__ == "__main__":
    main()
