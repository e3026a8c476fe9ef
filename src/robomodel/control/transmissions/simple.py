"""SimpleTransmission: one actuator, one joint, a reduction and a joint offset."""

from __future__ import annotations

from collections.abc import Sequence

from robomodel.control.transmissions.base import Transmission
from robomodel.control.transmissions.exceptions import TransmissionError

__all__ = ["SimpleTransmission"]


class SimpleTransmission(Transmission):
    """``τ_j = n τ_a; v_j = v_a / n; x_j = x_a / n + offset`` (and the inverse).

    From ros_control simple_transmission.h (same in ROS 2 transmission_interface).

    Args:
        reduction: Mechanical reduction ``n`` (non-zero).
        joint_offset: Joint position offset [rad or m].
    """

    num_actuators = 1
    num_joints = 1

    def __init__(self, reduction: float = 1.0, joint_offset: float = 0.0) -> None:
        if reduction == 0.0:
            raise TransmissionError("SimpleTransmission: the mechanical reduction must not be 0")
        self.reduction = reduction
        self.joint_offset = joint_offset

    def actuator_to_joint_effort(self, effort: Sequence[float]) -> list[float]:
        return [effort[0] * self.reduction]

    def actuator_to_joint_velocity(self, velocity: Sequence[float]) -> list[float]:
        return [velocity[0] / self.reduction]

    def actuator_to_joint_position(self, position: Sequence[float]) -> list[float]:
        return [position[0] / self.reduction + self.joint_offset]

    def joint_to_actuator_effort(self, effort: Sequence[float]) -> list[float]:
        return [effort[0] / self.reduction]

    def joint_to_actuator_velocity(self, velocity: Sequence[float]) -> list[float]:
        return [velocity[0] * self.reduction]

    def joint_to_actuator_position(self, position: Sequence[float]) -> list[float]:
        return [(position[0] - self.joint_offset) * self.reduction]
