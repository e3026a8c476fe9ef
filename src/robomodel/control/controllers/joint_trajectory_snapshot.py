"""What joint_trajectory_controller's bus adapter may read: a frozen snapshot of its state.

The controller makes one with :meth:`~.joint_trajectory.JointTrajectoryController.snapshot`;
:mod:`.joint_trajectory_services` (the FollowJointTrajectory action, ``~/query_state`` and
``~/controller_state``) reads nothing else, so the adapter cannot change the controller behind
its back and needs no import of the controller's module.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

from robomodel.control.controllers.joint_trajectory_goal import GoalHandle
from robomodel.control.controllers.trajectory import Trajectory

__all__ = ["TrajectoryControllerSnapshot"]


@dataclass(frozen=True, slots=True)
class TrajectoryControllerSnapshot:
    """The controller at ``time_s`` (the time of its last update) [s].

    Attributes:
        time_s: The controller's clock at its last update [s].
        active: Whether the controller is active (humble rejects goals otherwise).
        joints: The controlled joints, in the controller's order.
        positions: Measured positions, one per joint. [rad] or [m] by joint type.
        velocities: Measured velocities, one per joint, or empty without a velocity state.
        trajectory: The trajectory being followed (or held), if any.
        goal: The running FollowJointTrajectory goal, if any.
        commands: What was last written, by command interface kind (``position``,
            ``velocity``, ``acceleration``, ``effort``), one value per joint.
    """

    time_s: float
    active: bool
    joints: tuple[str, ...]
    positions: tuple[float, ...]
    velocities: tuple[float, ...]
    trajectory: Trajectory | None
    goal: GoalHandle | None
    commands: Mapping[str, tuple[float, ...]]
