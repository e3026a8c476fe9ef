"""ROS's client libraries on robomodel's runtime: the rclpy and rospy APIs, the message modules
(``from std_msgs.msg import String``) and the helper libraries that node code imports with them
(``tf2_ros``, ``tf``, ``ament_index_python``, ``rospkg``).

A user's node runs unchanged: ``import rclpy`` finds :mod:`robomodel.clientlibs.rclpy` through
the import finder of :mod:`.finder`, which the ``robomodel-clientlibs.pth`` file installs at
interpreter start. The finder comes last on ``sys.meta_path``, so a real ROS installation on the
path (a sourced ``setup.bash``) always wins.
"""
