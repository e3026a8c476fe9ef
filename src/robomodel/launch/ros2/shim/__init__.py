"""robomodel's implementation of the ``launch`` / ``launch_ros`` Python API.

The classes here behave as Humble/Jazzy ``launch`` and ``launch_ros`` describe them, enough for
real launch files; :mod:`robomodel.launch.ros2.importer` exposes them under the upstream module
names while a launch file is loaded. Nothing here is installed as a top-level package.
"""
