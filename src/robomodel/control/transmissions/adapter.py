"""Applying a robot's transmissions between actuator and joint spaces.

A hardware component that talks to actuators (a real driver, or a simulator that models the
motors) keeps actuator-space values and uses :class:`TransmissionSet` to turn joint commands
into actuator commands and actuator states into joint states, per interface kind, as
ros2_control's transmission interfaces do.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

from robomodel.control.transmissions.base import Transmission
from robomodel.control.transmissions.loader import _by_role, transmission_from_description
from robomodel.description.model import Robot

__all__ = ["BoundTransmission", "TransmissionSet"]

_KINDS = ("effort", "velocity", "position")


@dataclass(frozen=True, slots=True)
class BoundTransmission:
    """A transmission with the joint and actuator names it connects, in role order."""

    transmission: Transmission
    joints: tuple[str, ...]
    actuators: tuple[str, ...]


class TransmissionSet:
    """All transmissions of a robot.

    Args:
        bound: The transmissions; :meth:`from_robot` builds them from the description.
    """

    def __init__(self, bound: list[BoundTransmission]) -> None:
        self.bound = bound

    @classmethod
    def from_robot(cls, robot: Robot) -> TransmissionSet:
        """From the URDF ``<transmission>`` tags and those inside ``<ros2_control>`` blocks."""
        elements = list(robot.transmissions)
        for block in robot.ros2_control:
            elements.extend(block.transmissions)
        bound = []
        for element in elements:
            joints = tuple(str(getattr(j, "name", "")) for j in _by_role(element.joints, "joint"))
            actuators = tuple(
                str(getattr(a, "name", "")) for a in _by_role(element.actuators, "actuator")
            )
            bound.append(
                BoundTransmission(transmission_from_description(element), joints, actuators)
            )
        return cls(bound)

    @property
    def joint_names(self) -> tuple[str, ...]:
        return tuple(j for b in self.bound for j in b.joints)

    @property
    def actuator_names(self) -> tuple[str, ...]:
        return tuple(a for b in self.bound for a in b.actuators)

    def joint_to_actuator(self, kind: str, joint_values: Mapping[str, float]) -> dict[str, float]:
        """Joint ``effort``/``velocity``/``position`` values by joint name -> by actuator name."""
        out: dict[str, float] = {}
        for b in self.bound:
            if all(j in joint_values for j in b.joints):
                values = [joint_values[j] for j in b.joints]
                fn = getattr(b.transmission, f"joint_to_actuator_{kind}")
                out.update(zip(b.actuators, fn(values), strict=True))
        return out

    def actuator_to_joint(
        self, kind: str, actuator_values: Mapping[str, float]
    ) -> dict[str, float]:
        """Actuator values by actuator name -> joint values by joint name."""
        out: dict[str, float] = {}
        for b in self.bound:
            if all(a in actuator_values for a in b.actuators):
                values = [actuator_values[a] for a in b.actuators]
                fn = getattr(b.transmission, f"actuator_to_joint_{kind}")
                out.update(zip(b.joints, fn(values), strict=True))
        return out
