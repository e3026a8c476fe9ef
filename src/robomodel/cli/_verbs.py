"""The table of verbs: name, module and one-line help, known without importing any verb.

``robomodel --help`` lists the verbs from this table, and each verb module takes its help line
from here, so the list and the verbs cannot drift apart while a run imports only its own verb.
"""

from __future__ import annotations

__all__ = ["VERBS", "Verb", "verb_help"]


class Verb:
    """A sub-command: its name, the module whose ``register(subparsers)`` adds it, its help.

    A plain class rather than a dataclass or ``NamedTuple``: this module is on the path of
    ``robomodel --version``, which should not pay for importing ``dataclasses`` or ``typing``.
    """

    __slots__ = ("help", "module", "name")

    def __init__(self, name: str, module: str, help: str) -> None:
        self.name = name
        self.module = module
        self.help = help


VERBS: tuple[Verb, ...] = (
    Verb(
        "check", "robomodel.cli.check", "validate a URDF/xacro file (check_urdf, with line numbers)"
    ),
    Verb("graph", "robomodel.cli.graph", "draw the link/joint tree (urdf_to_graphviz)"),
    Verb(
        "new",
        "robomodel.cli.new",
        "create a robot description package (catkin_create_pkg, ros2 pkg create)",
    ),
    Verb("xacro", "robomodel.cli.xacro", "expand a xacro file (same output as ROS xacro 2.1.1)"),
    Verb("tf", "robomodel.cli.tf", "print the transform between two frames, as tf2_echo does"),
    Verb("frames", "robomodel.cli.frames", "draw the TF tree, as view_frames does"),
    Verb("fk", "robomodel.cli.fk", "forward kinematics: link poses in the root frame"),
    Verb("ik", "robomodel.cli.ik", "inverse kinematics: joint values for a link pose"),
    Verb("topic", "robomodel.cli.topic", "list, echo, publish and measure topics (ros2 topic)"),
    Verb("bag", "robomodel.cli.bag", "record, inspect and play bags (ros2 bag, rosbag)"),
    Verb("node", "robomodel.cli.node", "list the nodes and what each offers (ros2 node)"),
    Verb("param", "robomodel.cli.param", "inspect and change node parameters (ros2 param)"),
    Verb("service", "robomodel.cli.service", "list and call services (ros2 service)"),
    Verb(
        "log",
        "robomodel.cli.log",
        "the nodes' log lines from /rosout, filtered by node and severity (rqt_console)",
    ),
    Verb(
        "router",
        "robomodel.cli.router",
        "run a Zenoh router for ROS 2 (ros2 run rmw_zenoh_cpp rmw_zenohd)",
    ),
    Verb(
        "master", "robomodel.cli.master", "run a ROS 1 master with its parameter server (roscore)"
    ),
    Verb(
        "publish-state",
        "robomodel.cli.publish_state",
        "run robot_state_publisher + joint_state_publisher for a description",
    ),
    Verb("control", "robomodel.cli.control", "controller manager: run, list, load, switch"),
    Verb(
        "view",
        "robomodel.cli.view",
        "view descriptions in the browser: robot model, TF frames and joint sliders",
    ),
    Verb(
        "sim",
        "robomodel.cli.sim",
        "simulate a robot (Gazebo's role, on MuJoCo) with its controllers",
    ),
    Verb(
        "run",
        "robomodel.cli.run",
        "run one node as rosrun / ros2 run do (robomodel's nodes and your own Python nodes)",
    ),
    Verb(
        "launch",
        "robomodel.cli.launch",
        "run a ROS 1 or ROS 2 launch file with robomodel's nodes",
    ),
)

_HELP = {verb.name: verb.help for verb in VERBS}


def verb_help(name: str) -> str:
    """The one-line help of verb ``name`` (what ``robomodel --help`` lists)."""
    return _HELP[name]
