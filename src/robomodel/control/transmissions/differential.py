"""DifferentialTransmission: two actuators drive two joints through a differential."""

from __future__ import annotations

from collections.abc import Sequence

from robomodel.control.transmissions.base import Transmission
from robomodel.control.transmissions.exceptions import TransmissionError

__all__ = ["DifferentialTransmission"]


class DifferentialTransmission(Transmission):
    """The formulas of ros_control differential_transmission.h (identical in ROS 2).

    Args:
        actuator_reductions: ``ar[2]`` (non-zero).
        joint_reductions: ``jr[2]`` (non-zero).
        joint_offsets: ``off[2]`` [rad or m].
    """

    num_actuators = 2
    num_joints = 2

    def __init__(
        self,
        actuator_reductions: Sequence[float],
        joint_reductions: Sequence[float],
        joint_offsets: Sequence[float] = (0.0, 0.0),
    ) -> None:
        for what, values in (("actuator", actuator_reductions), ("joint", joint_reductions)):
            if len(values) != 2 or 0.0 in values:
                raise TransmissionError(
                    f"DifferentialTransmission: needs two non-zero {what} reductions, "
                    f"got {list(values)}"
                )
        self.ar = (float(actuator_reductions[0]), float(actuator_reductions[1]))
        self.jr = (float(joint_reductions[0]), float(joint_reductions[1]))
        self.off = (float(joint_offsets[0]), float(joint_offsets[1]))

    def actuator_to_joint_effort(self, effort: Sequence[float]) -> list[float]:
        (ar0, ar1), (jr0, jr1) = self.ar, self.jr
        return [
            jr0 * (effort[0] * ar0 + effort[1] * ar1),
            jr1 * (effort[0] * ar0 - effort[1] * ar1),
        ]

    def actuator_to_joint_velocity(self, velocity: Sequence[float]) -> list[float]:
        (ar0, ar1), (jr0, jr1) = self.ar, self.jr
        a, b = velocity[0] / ar0, velocity[1] / ar1
        return [(a + b) / (2.0 * jr0), (a - b) / (2.0 * jr1)]

    def actuator_to_joint_position(self, position: Sequence[float]) -> list[float]:
        (ar0, ar1), (jr0, jr1) = self.ar, self.jr
        a, b = position[0] / ar0, position[1] / ar1
        return [(a + b) / (2.0 * jr0) + self.off[0], (a - b) / (2.0 * jr1) + self.off[1]]

    def joint_to_actuator_effort(self, effort: Sequence[float]) -> list[float]:
        (ar0, ar1), (jr0, jr1) = self.ar, self.jr
        a, b = effort[0] / jr0, effort[1] / jr1
        return [(a + b) / (2.0 * ar0), (a - b) / (2.0 * ar1)]

    def joint_to_actuator_velocity(self, velocity: Sequence[float]) -> list[float]:
        (ar0, ar1), (jr0, jr1) = self.ar, self.jr
        a, b = velocity[0] * jr0, velocity[1] * jr1
        return [(a + b) * ar0, (a - b) * ar1]

    def joint_to_actuator_position(self, position: Sequence[float]) -> list[float]:
        (ar0, ar1), (jr0, jr1) = self.ar, self.jr
        a, b = (position[0] - self.off[0]) * jr0, (position[1] - self.off[1]) * jr1
        return [(a + b) * ar0, (a - b) * ar1]
