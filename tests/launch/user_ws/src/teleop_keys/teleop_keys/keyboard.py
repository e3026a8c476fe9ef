"""Drive a robot from the keyboard, as teleop_twist_keyboard does: keys read one at a time from
the terminal (raw mode), a geometry_msgs/Twist on ``cmd_vel`` (remap it with ``--ros-args -r
cmd_vel:=...``), repeated at 10 Hz so a diff-drive controller's command timeout does not stop
the robot between keys.

Written against robomodel's own node API (robomodel.runtime), with its ``--ros-args`` parser.
"""

import os
import select
import sys
import termios
import time
import tty

from robomodel.launch.node_args import parse_ros2_args
from robomodel.runtime import Context
from robomodel.runtime.msg.types.geometry_msgs import Twist, Vector3

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
    parsed = parse_ros2_args(sys.argv[1:], default_name="teleop_twist_keyboard")
    speed = float(parsed.params.get("speed", 0.5))
    turn = float(parsed.params.get("turn", 1.0))
    context = Context("zenoh")
    node = context.create_node(
        parsed.name or "teleop_twist_keyboard", remappings=dict(parsed.remaps)
    )
    publisher = node.create_publisher(Twist, "cmd_vel", 10)
    fd = sys.stdin.fileno()
    saved = termios.tcgetattr(fd)
    x = th = 0
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
            publisher.publish(Twist(linear=Vector3(x * speed, 0.0, 0.0),
                                    angular=Vector3(0.0, 0.0, th * turn)))  # fmt: skip
            context.spin_once(0.0)
    finally:
        publisher.publish(Twist())
        termios.tcsetattr(fd, termios.TCSADRAIN, saved)
        time.sleep(0.1)  # the last (stop) command leaves before the session closes
        context.shutdown()
    return 0
