"""Control: a ros2_control-compatible controller framework without ROS."""
