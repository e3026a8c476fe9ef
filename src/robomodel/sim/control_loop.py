"""A robot's ros2_control system inside the physics loop (what gazebo_ros2_control does).

:func:`simulated_components` builds the robot's hardware: simulator plugins
(``gazebo_ros2_control/GazeboSystem``, ``gz_ros2_control/GazeboSimSystem``, or ROS 1
``<transmission>`` tags as the ``gazebo_ros_control`` plugin reads them) become a
:class:`~robomodel.sim.hardware.SimSystem` on the MuJoCo state; other plugins (mock hardware)
are built as usual and do not touch the physics. :func:`control_cycle` makes the controller
manager and the callback the engine runs every ``1 / update_rate`` of sim time: read, update,
write, with the period in sim time.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from robomodel.control import ControlSystem
    from robomodel.control.config import ControllerConfig
    from robomodel.control.manager import ControllerManager
    from robomodel.runtime.context import Context
    from robomodel.sim.build.robot import BuiltRobot
    from robomodel.sim.hardware import SimSystem
    from robomodel.sim.schedule import StepCallback

__all__ = ["ControlCycle", "control_cycle", "simulated_components"]


@dataclass(frozen=True, slots=True)
class ControlCycle:
    """A control system and how the engine runs it: ``callback`` every ``every_steps``."""

    system: ControlSystem
    every_steps: int
    callback: StepCallback


def simulated_components(
    built: BuiltRobot, model: Any, data: Any
) -> tuple[list[Any], list[SimSystem]]:
    """The robot's hardware components, and those of them that act on the physics.

    Raises:
        ControlError: the robot has neither a ``<ros2_control>`` block nor transmissions.
    """
    from robomodel.control.exceptions import ControlError
    from robomodel.control.hardware import HARDWARE_PLUGINS, hardware_infos_from_robot
    from robomodel.sim.hardware import SIMULATOR_PLUGINS, SimSystem

    components: list[Any] = []
    simulated: list[SimSystem] = []
    for info in hardware_infos_from_robot(built.robot):
        derived = info.source == "<transmission> tags"
        if info.plugin in SIMULATOR_PLUGINS or derived:
            component = SimSystem(info, model, data, prefix=built.prefix)
            simulated.append(component)
            components.append(component)
        else:
            components.append(HARDWARE_PLUGINS[info.plugin](info, built.robot))
    if not components:
        raise ControlError(
            f"robot '{built.robot.name}' has no <ros2_control> block and no <transmission> "
            "tags, so the controllers have no hardware; add a <ros2_control> block with "
            "<plugin>gazebo_ros2_control/GazeboSystem</plugin>"
        )
    return components, simulated


def control_cycle(
    built: BuiltRobot,
    config: ControllerConfig,
    components: list[Any],
    *,
    timestep_s: float,
    context: Context | None,
    spawn: Sequence[str] | None,
    update_rate_hz: int | None,
    namespace: str | None,
    prepare: Callable[[ControllerManager], None] | None = None,
) -> ControlCycle:
    """The controller manager over ``components`` with ``config``'s controllers spawned, then
    ``prepare`` run on it, before its services are offered."""
    from robomodel.control import ControlSystem
    from robomodel.control.hardware import ResourceManager
    from robomodel.control.manager import ControllerManager

    resources = ResourceManager(components)
    rate = int(update_rate_hz or config.update_rate_hz)
    steps = max(1, round(1.0 / (rate * timestep_s)))
    manager = ControllerManager(
        resources,
        context=context,
        robot=built.robot,
        update_rate_hz=rate,
        namespace=namespace if namespace is not None else config.namespace,
        parameters={**config.manager_params, "use_sim_time": True},
        serve=False,
    )
    manager.set_config(config)
    manager.spawn([s.name for s in config.controllers] if spawn is None else list(spawn))
    if prepare is not None:
        prepare(manager)
    manager.serve()
    period = steps * timestep_s

    def cycle(time_s: float) -> None:
        manager.time_s = time_s
        manager.read(time_s, period)
        manager.update(time_s, period)
        manager.write(time_s, period)

    return ControlCycle(ControlSystem(resources, manager, config), steps, cycle)
