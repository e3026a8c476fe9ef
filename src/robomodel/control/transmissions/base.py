"""The transmission interface: maps actuator space to joint space and back.

Each direction handles effort, velocity and position (transmission_interface's
``actuator_to_joint`` / ``joint_to_actuator``). Values are sequences ordered by role
(``actuator1``, ``actuator2``; ``joint1``, ``joint2``).
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from collections.abc import Sequence

__all__ = ["Transmission"]


class Transmission(ABC):
    """A mechanical transmission between ``num_actuators`` actuators and ``num_joints`` joints."""

    num_actuators: int
    num_joints: int

    @abstractmethod
    def actuator_to_joint_effort(self, effort: Sequence[float]) -> list[float]: ...

    @abstractmethod
    def actuator_to_joint_velocity(self, velocity: Sequence[float]) -> list[float]: ...

    @abstractmethod
    def actuator_to_joint_position(self, position: Sequence[float]) -> list[float]: ...

    @abstractmethod
    def joint_to_actuator_effort(self, effort: Sequence[float]) -> list[float]: ...

    @abstractmethod
    def joint_to_actuator_velocity(self, velocity: Sequence[float]) -> list[float]: ...

    @abstractmethod
    def joint_to_actuator_position(self, position: Sequence[float]) -> list[float]: ...
