"""Simulated sensors declared by ``<gazebo reference=...><sensor>``: lidar, sonar, IMU, contact."""
