"""``rclpy.impl``: the modules user code imports from it (``rclpy.impl.logging_severity``,
``rclpy.impl.rcutils_logger``); rclpy's C extension behind it has no counterpart."""
