"""Kinematics: batched forward kinematics, Jacobians and inverse kinematics.

``Kinematics(robot)`` compiles a :class:`~robomodel.description.Robot` once; ``fk``,
``jacobian`` and ``ik`` then take joint configurations ``q`` of shape ``(n_q,)`` or
``(*batch, n_q)``.
"""

from robomodel.kinematics._ik_options import IKOptions
from robomodel.kinematics.dynamics import Dynamics
from robomodel.kinematics.exceptions import (
    ConfigurationError,
    KinematicsError,
    KinematicsWarning,
    MimicCycleError,
    UnreachableError,
    ZeroAxisError,
)
from robomodel.kinematics.kinematics import Kinematics

__all__ = [
    "ConfigurationError",
    "Dynamics",
    "IKOptions",
    "Kinematics",
    "KinematicsError",
    "KinematicsWarning",
    "MimicCycleError",
    "UnreachableError",
    "ZeroAxisError",
]
