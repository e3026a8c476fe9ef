"""The description layer: the URDF model, its parser, writer and validation, and ROS packages.

The names are re-exported lazily (PEP 562), so that importing one module of this layer (say
``robomodel.description.packages`` for xacro's ``$(find)``) does not load the others.
"""

from __future__ import annotations

import importlib

TYPE_CHECKING = False  # typing.TYPE_CHECKING without importing typing (mypy knows the name)
if TYPE_CHECKING:
    from robomodel.description.model import (
        Box,
        Calibration,
        Capsule,
        Collision,
        ComponentInterfaces,
        Cylinder,
        Dynamics,
        GazeboBlock,
        Geometry,
        Inertia,
        Inertial,
        Interface,
        Joint,
        JointType,
        KinematicTree,
        Limit,
        Link,
        Material,
        Mesh,
        Mimic,
        Origin,
        RawElement,
        Robot,
        Ros2Control,
        SafetyController,
        SourceSpan,
        SourceText,
        Sphere,
        Transmission,
        TransmissionActuator,
        TransmissionJoint,
        TransmissionStyle,
        TreeError,
        UnknownNameError,
        Visual,
    )
    from robomodel.description.packages import Package, PackageIndex
    from robomodel.description.urdf.reader import ParseResult, URDFWarning, parse_urdf, read_urdf
    from robomodel.description.validate import validate, validate_resources

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
    "Package",
    "PackageIndex",
    "ParseResult",
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
    "URDFWarning",
    "UnknownNameError",
    "Visual",
    "parse_urdf",
    "read_urdf",
    "validate",
    "validate_resources",
]

_MODULE_OF: dict[str, str] = {
    "Box": "robomodel.description.model",
    "Calibration": "robomodel.description.model",
    "Capsule": "robomodel.description.model",
    "Collision": "robomodel.description.model",
    "ComponentInterfaces": "robomodel.description.model",
    "Cylinder": "robomodel.description.model",
    "Dynamics": "robomodel.description.model",
    "GazeboBlock": "robomodel.description.model",
    "Geometry": "robomodel.description.model",
    "Inertia": "robomodel.description.model",
    "Inertial": "robomodel.description.model",
    "Interface": "robomodel.description.model",
    "Joint": "robomodel.description.model",
    "JointType": "robomodel.description.model",
    "KinematicTree": "robomodel.description.model",
    "Limit": "robomodel.description.model",
    "Link": "robomodel.description.model",
    "Material": "robomodel.description.model",
    "Mesh": "robomodel.description.model",
    "Mimic": "robomodel.description.model",
    "Origin": "robomodel.description.model",
    "RawElement": "robomodel.description.model",
    "Robot": "robomodel.description.model",
    "Ros2Control": "robomodel.description.model",
    "SafetyController": "robomodel.description.model",
    "SourceSpan": "robomodel.description.model",
    "SourceText": "robomodel.description.model",
    "Sphere": "robomodel.description.model",
    "Transmission": "robomodel.description.model",
    "TransmissionActuator": "robomodel.description.model",
    "TransmissionJoint": "robomodel.description.model",
    "TransmissionStyle": "robomodel.description.model",
    "TreeError": "robomodel.description.model",
    "UnknownNameError": "robomodel.description.model",
    "Visual": "robomodel.description.model",
    "Package": "robomodel.description.packages",
    "PackageIndex": "robomodel.description.packages",
    "ParseResult": "robomodel.description.urdf.reader",
    "URDFWarning": "robomodel.description.urdf.reader",
    "parse_urdf": "robomodel.description.urdf.reader",
    "read_urdf": "robomodel.description.urdf.reader",
    "validate": "robomodel.description.validate",
    "validate_resources": "robomodel.description.validate",
}


def __getattr__(name: str) -> object:
    module = _MODULE_OF.get(name)
    if module is None:
        raise AttributeError(f"module 'robomodel.description' has no attribute '{name}'")
    value = getattr(importlib.import_module(module), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted({*globals(), *__all__})
