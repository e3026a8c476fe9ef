"""A loaded controller: its instance, parameters, rate and node (controller_manager's
``ControllerSpec`` + ``load_controller``'s creation step)."""

from __future__ import annotations

import enum
import logging
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from robomodel.control.controllers.base import (
    ControllerInterface,
    InterfaceConfiguration,
    InterfaceSelection,
)
from robomodel.control.controllers.registry import create_controller
from robomodel.errors import RobomodelError

if TYPE_CHECKING:
    from robomodel.control.hardware.resource_manager import ResourceManager
    from robomodel.description.model import Robot
    from robomodel.runtime.context import Context
    from robomodel.runtime.node import Node

__all__ = [
    "ControllerEntry",
    "Strictness",
    "controller_info",
    "create_entry",
    "required_interfaces",
]

log = logging.getLogger("robomodel.control")


class Strictness(enum.IntEnum):
    """controller_manager_msgs/SwitchController strictness."""

    BEST_EFFORT = 1
    STRICT = 2


@dataclass(eq=False)
class ControllerEntry:
    """One controller the manager holds (any state)."""

    name: str
    type_name: str
    controller: ControllerInterface
    params: dict[str, Any]
    fallback: tuple[str, ...] = ()
    update_rate_hz: int = 0
    factor: int = 1
    claimed: tuple[str, ...] = ()
    state_names: tuple[str, ...] = ()
    node: Node | None = None
    extra: dict[str, Any] = field(default_factory=dict)
    listed_type: str = ""  # the type as the YAML names it (a ROS 1 type robomodel maps)


def _rate(name: str, params: Mapping[str, Any], manager_rate_hz: int) -> int:
    """The controller's rate: the manager's, or a divisor of it (controller_interface_base.cpp
    ``configure()`` adjusts a rate that does not divide the manager's)."""
    rate = int(params.get("update_rate", manager_rate_hz))
    if rate <= 0 or rate > manager_rate_hz:
        return manager_rate_hz
    if manager_rate_hz % rate != 0:
        rate = manager_rate_hz // round(manager_rate_hz / rate)
        log.warning("%s: update rate adjusted to %d Hz (a divisor of the manager's)", name, rate)
    return rate


def create_entry(
    name: str,
    type_name: str,
    params: dict[str, Any],
    *,
    context: Context | None,
    namespace: str,
    robot: Robot | None,
    manager_rate_hz: int,
) -> ControllerEntry:
    """Create and ``init`` controller ``name`` of ``type_name`` with ``params``.

    Raises:
        RobomodelError: an unknown type or a controller refusing its parameters.
    """
    controller = create_controller(type_name)
    rate = _rate(name, params, manager_rate_hz)
    node = None
    if context is not None:
        node = context.create_node(
            name, namespace, parameters=params, allow_undeclared_parameters=True
        )
    try:
        controller.init(name, params, node=node, robot=robot, update_rate_hz=rate)
    except RobomodelError:
        if node is not None:
            node.destroy()
        raise
    fallback = params.get("fallback_controllers", ())
    return ControllerEntry(
        name,
        type_name,
        controller,
        params,
        tuple([fallback] if isinstance(fallback, str) else fallback),
        rate,
        max(1, manager_rate_hz // rate),
        node=node,
    )


def required_interfaces(
    controller: ControllerInterface, resources: ResourceManager
) -> tuple[list[str], list[str]]:
    """The full names of the command and state interfaces ``controller`` asks for (``ALL``
    expands to every interface of the hardware, ``NONE`` to none)."""
    commands = _selected(controller.command_interface_configuration(), resources.commands.names)
    states = _selected(controller.state_interface_configuration(), resources.states.names)
    return commands, states


def _selected(config: InterfaceConfiguration, available: Iterable[str]) -> list[str]:
    """The interfaces a configuration selects among ``available`` (ALL, NONE or its names)."""
    if config.selection is InterfaceSelection.ALL:
        return list(available)
    if config.selection is InterfaceSelection.NONE:
        return []
    return list(config.names)


def controller_info(entry: ControllerEntry, resources: ResourceManager) -> dict[str, Any]:
    """One controller as ``list_controllers`` reports it."""
    commands, states = required_interfaces(entry.controller, resources)
    return {
        "name": entry.name,
        "type": entry.listed_type or entry.type_name,
        "state": entry.controller.state.value,
        "started": bool(entry.extra.get("started")),  # ever active since it was loaded
        "update_rate": entry.update_rate_hz,
        "claimed_interfaces": list(entry.claimed),
        "required_command_interfaces": commands,
        "required_state_interfaces": states,
    }
