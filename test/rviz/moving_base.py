#!/usr/bin/python3
"""Publishes nav_msgs/Odometry on `odom` for the rviz display's moving-base run
(test/rviz/moving_base.launch): a base that walks along x of frame `odom` at ~speed m/s
(default 0.5; 10 m in 20 s, far out of a fixed view), its twist in the base's own frame
(child_frame_id ~base, default base_link), at ~rate Hz, stamped now."""
import rospy
from nav_msgs.msg import Odometry


def main():
    rospy.init_node("moving_base")
    speed = rospy.get_param("~speed", 0.5)
    base = rospy.get_param("~base", "base_link")
    pub = rospy.Publisher("odom", Odometry, queue_size=10)
    rate = rospy.Rate(rospy.get_param("~rate", 50.0))
    start = rospy.Time.now()
    while not rospy.is_shutdown():
        now = rospy.Time.now()
        msg = Odometry()
        msg.header.stamp, msg.header.frame_id, msg.child_frame_id = now, "odom", base
        msg.pose.pose.position.x = speed * (now - start).to_sec()
        msg.pose.pose.orientation.w = 1
        msg.twist.twist.linear.x = speed
        pub.publish(msg)
        try:
            rate.sleep()
        except rospy.ROSInterruptException:
            break


if __name__ == "__main__":
    main()
