"""Drive a robot from the keyboard, as teleop_twist_keyboard does: keys read one at a time from
the terminal (raw mode), a geometry_msgs/Twist on ``cmd_vel`` (remap it with ``--ros-args -r
cmd_vel:=...``), repeated at 10 Hz so a diff-drive controller's command timeout does not stop
the robot between keys.

Written against rclpy, as teleop_twist_keyboard's ROS 2 node is: parameters ``speed`` and
``turn``, ``rclpy.spin`` on a thread of its own while the main thread reads the keys.
"""

import os
import select
import sys
import termios
import threading
import time
import tty

import rclpy
from geometry_msgs.msg import Twist

HELP = """Reading from the keyboard and Publishing to Twist!
---------------------------
Moving around:
   u    i    o
   j    k    l
        ,
k: stop, q: quit"""

MOVES = {
    "i": (1, 0), "o": (1, -1), "j": (0, 1), "l": (0, -1), "u": (1, 1),
    ",": (-1, 0), "k": (0, 0),
}  # fmt: skip


def read_key(fd, timeout_s):
    ready, _, _ = select.select([fd], [], [], timeout_s)
    return os.read(fd, 1).decode(errors="replace") if ready else ""


def main():
    rclpy.init()
    node = rclpy.create_node("teleop_twist_keyboard")
    speed = node.declare_parameter("speed", 0.5).value
    turn = node.declare_parameter("turn", 1.0).value
    publisher = node.create_publisher(Twist, "cmd_vel", 10)
    spinner = threading.Thread(target=rclpy.spin, args=(node,), daemon=True)
    spinner.start()
    fd = sys.stdin.fileno()
    saved = termios.tcgetattr(fd)
    x = th = 0
    twist = Twist()
    try:
        tty.setraw(fd)
        sys.stdout.write(HELP.replace("\n", "\r\n") + "\r\n")
        sys.stdout.flush()
        while True:
            key = read_key(fd, 0.1)
            if key in ("q", "\x03"):
                break
            if key in MOVES:
                x, th = MOVES[key]
                sys.stdout.write(f"currently:\tx {x * speed:.2f}\tyaw {th * turn:.2f}\r\n")
                sys.stdout.flush()
            twist.linear.x = x * speed
            twist.angular.z = th * turn
            publisher.publish(twist)
    finally:
        publisher.publish(Twist())
        termios.tcsetattr(fd, termios.TCSADRAIN, saved)
        time.sleep(0.1)  # the last (stop) command leaves before the session closes
        rclpy.shutdown()
        spinner.join()
    return 0
