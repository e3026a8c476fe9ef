"""The URDF model: frozen dataclasses, plain data, no I/O."""

from robomodel.description.model.extensions import (
    ComponentInterfaces,
    GazeboBlock,
    Interface,
    Ros2Control,
    Transmission,
    TransmissionActuator,
    TransmissionJoint,
    TransmissionStyle,
)
from robomodel.description.model.geometry import (
    Box,
    Capsule,
    Collision,
    Cylinder,
    Geometry,
    Material,
    Mesh,
    Sphere,
    Visual,
)
from robomodel.description.model.joint import (
    Calibration,
    Dynamics,
    Joint,
    JointType,
    Limit,
    Mimic,
    SafetyController,
)
from robomodel.description.model.link import Inertia, Inertial, Link
from robomodel.description.model.pose import Origin
from robomodel.description.model.raw import RawElement
from robomodel.description.model.robot import Robot, UnknownNameError
from robomodel.description.model.source import SourceSpan, SourceText
from robomodel.description.model.tree import KinematicTree, TreeError

__all__ = [
    "Box",
    "Calibration",
    "Capsule",
    "Collision",
    "ComponentInterfaces",
    "Cylinder",
    "Dynamics",
    "GazeboBlock",
    "Geometry",
    "Inertia",
    "Inertial",
    "Interface",
    "Joint",
    "JointType",
    "KinematicTree",
    "Limit",
    "Link",
    "Material",
    "Mesh",
    "Mimic",
    "Origin",
    "RawElement",
    "Robot",
    "Ros2Control",
    "SafetyController",
    "SourceSpan",
    "SourceText",
    "Sphere",
    "Transmission",
    "TransmissionActuator",
    "TransmissionJoint",
    "TransmissionStyle",
    "TreeError",
    "UnknownNameError",
    "Visual",
]
