"""robomodel: the ROS robot-modelling workflow as one pip-installable package."""

from robomodel._version import __version__
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
