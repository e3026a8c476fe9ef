"""Helpers for scripted runs (``robomodel sim --cmd-vel ... --report json``): a constant
Twist publisher for the diff-drive controller and a watcher of its odometry."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from robomodel.runtime.msg.geometry_msgs import Twist, TwistStamped, Vector3
from robomodel.runtime.msg.nav_msgs import Odometry
from robomodel.runtime.msg.std_msgs import Header
from robomodel.sim.exceptions import SimulationError

if TYPE_CHECKING:
    from robomodel.control import ControlSystem
    from robomodel.runtime.context import Context
    from robomodel.sim.engine import Simulation

__all__ = ["CmdVelDriver", "OdomWatcher", "diff_drive_controller"]


def diff_drive_controller(system: ControlSystem | None) -> Any:
    """The first diff-drive controller of ``system`` (or ``None``)."""
    if system is None:
        return None
    for entry in system.manager.entries.values():
        if entry.type_name.endswith("DiffDriveController"):
            return entry.controller
    return None


@dataclass
class OdomWatcher:
    """Keeps the last message of the diff-drive controller's ``~/odom``."""

    last: Odometry | None = None

    @classmethod
    def attach(cls, system: ControlSystem, context: Context) -> OdomWatcher | None:
        controller = diff_drive_controller(system)
        if controller is None or controller.node is None:
            return None
        watcher = cls()
        topic = controller.node.resolve_topic_name("~/odom")
        node = context.create_node("sim_odom_watcher")
        node.create_subscription(Odometry, topic, watcher._on_odom, 10)
        return watcher

    def _on_odom(self, msg: Odometry) -> None:
        self.last = msg


class CmdVelDriver:
    """Publishes a constant command to the diff-drive controller at 10 Hz of sim time."""

    @staticmethod
    def attach(
        sim: Simulation,
        system: ControlSystem | None,
        context: Context,
        cmd: tuple[float, float, float],
        *,
        topic: str | None = None,
    ) -> None:
        controller = diff_drive_controller(system)
        stamped = bool(getattr(controller, "use_stamped_vel", False)) and topic is None
        if topic is None:
            if controller is None or controller.node is None:
                raise SimulationError(
                    "--cmd-vel needs a diff_drive_controller in --controllers (or --cmd-vel-topic)"
                )
            name = "~/cmd_vel" if stamped else controller.unstamped_topic
            topic = controller.node.resolve_topic_name(name)
        node = context.create_node("sim_cmd_vel")
        twist = Twist(linear=Vector3(cmd[0], cmd[1], 0.0), angular=Vector3(0.0, 0.0, cmd[2]))
        if stamped:
            pub_s = node.create_publisher(TwistStamped, topic, 10)
            sim.every(
                10.0, lambda t: pub_s.publish(TwistStamped(header=Header(), twist=twist)), order=-2
            )
        else:
            pub = node.create_publisher(Twist, topic, 10)
            sim.every(10.0, lambda t: pub.publish(twist), order=-2)
