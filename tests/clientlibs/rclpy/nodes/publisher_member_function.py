"""A talker as the ROS 2 tutorial "Writing a simple publisher and subscriber (Python)" writes
it, run unchanged by robomodel's rclpy (tests/clientlibs/rclpy/test_zenoh.py)."""

import rclpy
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node
from std_msgs.msg import String


class MinimalPublisher(Node):
    def __init__(self):
        super().__init__("minimal_publisher")
        self.publisher_ = self.create_publisher(String, "topic", 10)
        timer_period = 0.05  # seconds
        self.timer = self.create_timer(timer_period, self.timer_callback)
        self.i = 0

    def timer_callback(self):
        msg = String()
        msg.data = "Hello World: %d" % self.i  # noqa: UP031 (the tutorial's own line)
        self.publisher_.publish(msg)
        self.get_logger().info('Publishing: "%s"' % msg.data)  # noqa: UP031
        self.i += 1


def main(args=None):
    try:
        with rclpy.init(args=args):
            minimal_publisher = MinimalPublisher()
            rclpy.spin(minimal_publisher)
    except (KeyboardInterrupt, ExternalShutdownException):
        pass


if __name__ == "__main__":
    main()
