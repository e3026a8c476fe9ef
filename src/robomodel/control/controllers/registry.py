"""Controller types by name (``type:`` in the YAML)."""

from __future__ import annotations

from collections.abc import Callable

from robomodel.control.controllers.base import ControllerInterface
from robomodel.control.controllers.diff_drive import DiffDriveController
from robomodel.control.controllers.exceptions import UnknownControllerTypeError
from robomodel.control.controllers.forward_command import (
    EffortGroupController,
    ForwardCommandController,
    PositionGroupController,
    SingleJointForwardController,
    VelocityGroupController,
)
from robomodel.control.controllers.gravity_compensation import GravityCompensationController
from robomodel.control.controllers.joint_position import JointPositionController
from robomodel.control.controllers.joint_state_broadcaster import JointStateBroadcaster
from robomodel.control.controllers.joint_trajectory import JointTrajectoryController

__all__ = ["CONTROLLER_TYPES", "create_controller", "register_controller_type"]

CONTROLLER_TYPES: dict[str, Callable[[], ControllerInterface]] = {
    cls.type_name: cls
    for cls in (
        JointStateBroadcaster,
        ForwardCommandController,
        PositionGroupController,
        VelocityGroupController,
        EffortGroupController,
        SingleJointForwardController,
        JointPositionController,
        GravityCompensationController,
        JointTrajectoryController,
        DiffDriveController,
    )
}


def register_controller_type(type_name: str, factory: Callable[[], ControllerInterface]) -> None:
    """Make ``type: type_name`` create controllers with ``factory``."""
    CONTROLLER_TYPES[type_name] = factory


def create_controller(type_name: str) -> ControllerInterface:
    """A new controller of ``type_name`` (error with close matches for unknown types)."""
    try:
        factory = CONTROLLER_TYPES[type_name]
    except KeyError:
        raise UnknownControllerTypeError(type_name, tuple(sorted(CONTROLLER_TYPES))) from None
    return factory()
