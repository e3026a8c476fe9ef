"""Helpers for scripted runs (``robomodel sim --cmd-vel ... --report json``): a constant
command for the diff-drive controller, applied at fixed sim times, and its odometry."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from robomodel.runtime.msg.types.geometry_msgs import Twist, TwistStamped, Vector3
from robomodel.runtime.msg.types.std_msgs import Header
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
    """The diff-drive controller's odometry, read in-process at the sim time of the report.

    Reading the controller (not the last ``~/odom`` message off the bus) makes a report
    depend on the simulation alone: a bus message arrives at a wall-clock time, so under load
    the "last" one was from an earlier sim time and the numbers changed from run to run.
    """

    controller: Any

    @classmethod
    def attach(cls, system: ControlSystem, context: Context) -> OdomWatcher | None:
        controller = diff_drive_controller(system)
        if controller is None:
            return None
        return cls(controller)

    def pose(self) -> tuple[float, float, float] | None:
        """``(x [m], y [m], yaw [rad])`` in the odom frame, None before the first update."""
        odometry = getattr(self.controller, "odometry", None)
        if odometry is None:
            return None
        return float(odometry.x), float(odometry.y), float(odometry.heading)


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
        namespace = controller.node.namespace if controller and controller.node else "/"
        node = context.create_node("sim_cmd_vel", namespace)
        twist = Twist(linear=Vector3(cmd[0], cmd[1], 0.0), angular=Vector3(0.0, 0.0, cmd[2]))
        if (
            controller is not None
            and controller.node is not None
            and topic
            == (
                controller.node.resolve_topic_name(
                    "~/cmd_vel" if stamped else controller.unstamped_topic
                )
            )
        ):
            # The command line's input is applied in-process at fixed sim times (every 0.1 s of
            # sim time, before the controllers update), so the same command gives the same run
            # to the last digit. It still goes out on the topic for anyone watching; arriving
            # later over the bus it sets the same values again.
            sim.every(
                10.0,
                lambda t: controller.set_command(cmd[0], cmd[2], t if t > 0.0 else None),
                order=-3,
            )
        if stamped:
            pub_s = node.create_publisher(TwistStamped, topic, 10)
            sim.every(
                10.0, lambda t: pub_s.publish(TwistStamped(header=Header(), twist=twist)), order=-2
            )
        else:
            pub = node.create_publisher(Twist, topic, 10)
            sim.every(10.0, lambda t: pub.publish(twist), order=-2)
