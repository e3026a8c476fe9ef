"""ROS 2's ``sensor_msgs_py`` (``from sensor_msgs_py import point_cloud2``): the helpers for
``sensor_msgs/PointCloud2`` that ROS 2 Python nodes import beside ``sensor_msgs.msg``."""
