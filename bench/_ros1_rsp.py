"""ROS 1 side of bench_runtime.py: rospy driver and /tf sink around Debian's C++
robot_state_publisher. Runs under Debian's ``/usr/bin/python3`` (rospy), not robomodel's venv.

``driver NAMES_JSON SECONDS RATE``: publishes /joint_states (stamp = wall time) at RATE for
SECONDS after one calibration message stamped 1.0 s, then prints a JSON summary.
``sink SECONDS``: records arrival − stamp of each /tf; the first message (the calibration one)
gives robot_state_publisher's own shift of the stamp (ROS 1 future-dates /tf by its publish
interval), which is subtracted. Prints the latencies as JSON.
"""

from __future__ import annotations

import json
import sys
import time

from _common import paced_sends  # this script's folder is on the path


def driver(names: list[str], seconds: float, rate: float) -> None:
    import rospy
    from sensor_msgs.msg import JointState

    rospy.init_node("bench_driver", disable_signals=True)
    pub = rospy.Publisher("/joint_states", JointState, queue_size=1000, tcp_nodelay=True)
    while pub.get_num_connections() < 1:
        time.sleep(0.05)
    time.sleep(2.0)  # the sink connects to robot_state_publisher's /tf meanwhile
    msg = JointState(name=names, position=[0.0] * len(names))
    msg.header.stamp = rospy.Time.from_sec(1.0)
    pub.publish(msg)
    time.sleep(0.5)
    print("start", flush=True)
    own0 = time.process_time()
    positions = [0.0] * len(names)

    def send(k: int) -> None:
        positions[0] = 0.001 * k
        msg = JointState(name=names, position=list(positions))
        msg.header.stamp = rospy.Time.from_sec(time.time())
        pub.publish(msg)

    sent, elapsed = paced_sends(seconds, rate, send)
    own = time.process_time() - own0
    print(json.dumps({"sent": sent, "elapsed": elapsed, "cpu": own}), flush=True)


def sink(seconds: float) -> None:
    import rospy
    from tf2_msgs.msg import TFMessage

    latencies: list[float] = []
    arrivals: list[float] = []
    shift: list[float] = []

    def on_tf(msg: TFMessage) -> None:
        now = time.time()
        stamp = msg.transforms[0].header.stamp.to_sec()
        if not shift:
            if stamp < 100.0:  # the calibration message, stamped 1.0 s
                shift.append(stamp - 1.0)
            return
        latencies.append(now - stamp + shift[0])
        arrivals.append(time.monotonic())

    rospy.init_node("bench_sink", disable_signals=True)
    rospy.Subscriber("/tf", TFMessage, on_tf, queue_size=1000, tcp_nodelay=True)
    print("ready", flush=True)
    time.sleep(seconds)
    print(json.dumps({"latencies": latencies, "arrivals": arrivals, "shift": shift}), flush=True)


if __name__ == "__main__":
    if sys.argv[1] == "driver":
        driver(json.loads(sys.argv[2]), float(sys.argv[3]), float(sys.argv[4]))
    else:
        sink(float(sys.argv[2]))
