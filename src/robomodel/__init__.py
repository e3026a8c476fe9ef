"""robomodel: the ROS robot-modelling workflow as one pip-installable package.

The names below are re-exported lazily (PEP 562): ``import robomodel`` loads no sub-package, so
a command such as ``robomodel xacro`` pays only for what it uses; ``robomodel.Robot`` imports
the description layer on first access.
"""

from __future__ import annotations

from robomodel._lazy import lazy_exports
from robomodel._version import __version__

TYPE_CHECKING = False  # typing.TYPE_CHECKING without importing typing (mypy knows the name)

if TYPE_CHECKING:
    from robomodel.description import PackageIndex, Robot, parse_urdf, read_urdf
    from robomodel.errors import InputError, RobomodelError
    from robomodel.kinematics import Kinematics
    from robomodel.loading import load

__all__ = [
    "InputError",
    "Kinematics",
    "PackageIndex",
    "RobomodelError",
    "Robot",
    "__version__",
    "load",
    "parse_urdf",
    "read_urdf",
]

_MODULE_OF: dict[str, str] = {
    "InputError": "robomodel.errors",
    "Kinematics": "robomodel.kinematics",
    "PackageIndex": "robomodel.description",
    "RobomodelError": "robomodel.errors",
    "Robot": "robomodel.description",
    "load": "robomodel.loading",
    "parse_urdf": "robomodel.description",
    "read_urdf": "robomodel.description",
}


__getattr__, __dir__ = lazy_exports(__name__, _MODULE_OF, globals(), __all__)
