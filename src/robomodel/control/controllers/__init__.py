"""Controllers: the interface and the standard ros2_controllers / ros_controllers types."""

from robomodel.control.controllers.base import (
    ControllerInterface,
    ControllerState,
    InterfaceConfiguration,
    InterfaceSelection,
)
from robomodel.control.controllers.diff_drive import DiffDriveController
from robomodel.control.controllers.exceptions import ControllerError, UnknownControllerTypeError
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
from robomodel.control.controllers.joint_trajectory import (
    GoalHandle,
    GoalStatus,
    JointTrajectoryController,
)
from robomodel.control.controllers.odometry import Odometry, RollingMean
from robomodel.control.controllers.registry import (
    CONTROLLER_TYPES,
    create_controller,
    register_controller_type,
)
from robomodel.control.controllers.speed_limiter import SpeedLimiter
from robomodel.control.controllers.trajectory import Trajectory, TrajectoryPoint

__all__ = [
    "CONTROLLER_TYPES",
    "ControllerError",
    "ControllerInterface",
    "ControllerState",
    "DiffDriveController",
    "EffortGroupController",
    "ForwardCommandController",
    "GoalHandle",
    "GoalStatus",
    "GravityCompensationController",
    "InterfaceConfiguration",
    "InterfaceSelection",
    "JointPositionController",
    "JointStateBroadcaster",
    "JointTrajectoryController",
    "Odometry",
    "PositionGroupController",
    "RollingMean",
    "SingleJointForwardController",
    "SpeedLimiter",
    "Trajectory",
    "TrajectoryPoint",
    "UnknownControllerTypeError",
    "VelocityGroupController",
    "create_controller",
    "register_controller_type",
]
