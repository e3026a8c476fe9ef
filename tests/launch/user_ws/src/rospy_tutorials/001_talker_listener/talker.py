#!/usr/bin/env python3
"""Publishes 'hello world <time>' on chatter at 10 Hz."""

import contextlib

import rospy
from std_msgs.msg import String


def talker():
    pub = rospy.Publisher("chatter", String, queue_size=10)
    rospy.init_node("talker", anonymous=True)
    rate = rospy.Rate(10)
    while not rospy.is_shutdown():
        text = f"hello world {rospy.get_time()}"
        rospy.loginfo(text)
        pub.publish(text)
        rate.sleep()


if __name__ == "__main__":
    with contextlib.suppress(rospy.ROSInterruptException):
        talker()
