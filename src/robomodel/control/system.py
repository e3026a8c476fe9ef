"""One call from a description and a controller file to a running controller manager."""

from __future__ import annotations

import os
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

from robomodel.control.config import ControllerConfig, load_controller_config
from robomodel.control.exceptions import ControlError
from robomodel.control.hardware import ResourceManager, hardware_from_robot
from robomodel.control.manager import ControllerManager

if TYPE_CHECKING:
    from robomodel.description.model import Robot
    from robomodel.runtime.context import Context

__all__ = ["ControlSystem"]


@dataclass
class ControlSystem:
    """Hardware, manager and configuration, as ``ros2_control_node`` plus the spawner.

    Use :meth:`build`; then ``system.manager.step()`` or ``system.manager.start()``.
    """

    resources: ResourceManager
    manager: ControllerManager
    config: ControllerConfig

    @classmethod
    def build(
        cls,
        robot: Robot,
        controllers: str | os.PathLike[str] | ControllerConfig,
        *,
        context: Context | None = None,
        spawn: Sequence[str] | None = None,
        update_rate_hz: int | None = None,
        name: str = "controller_manager",
        unknown_hardware_as_mock: bool = False,
        prepare: Callable[[ControllerManager], None] | None = None,
    ) -> ControlSystem:
        """Build the hardware of ``robot``, load ``controllers`` and spawn them (all by default).

        Raises:
            ControlError: no hardware (no ``<ros2_control>`` and no ``<transmission>``), or any
                controller error.
        """
        config = (
            controllers
            if isinstance(controllers, ControllerConfig)
            else load_controller_config(controllers)
        )
        components = hardware_from_robot(robot, unknown_as_mock=unknown_hardware_as_mock)
        if not components:
            raise ControlError(
                f"robot '{robot.name}' has no <ros2_control> block and no <transmission> tags, "
                "so there is no hardware to control; add a <ros2_control> block with "
                "<plugin>mock_components/GenericSystem</plugin>"
            )
        resources = ResourceManager(components)
        manager = ControllerManager(
            resources,
            context=context,
            robot=robot,
            update_rate_hz=update_rate_hz or config.update_rate_hz,
            name=name,
            namespace=config.namespace,
            parameters=config.manager_params,
            serve=False,
        )
        manager.set_config(config)
        names = [s.name for s in config.controllers] if spawn is None else list(spawn)
        manager.spawn(names)
        if prepare is not None:  # before the services: a spawner finds the manager ready
            prepare(manager)
        manager.serve()
        return cls(resources, manager, config)
