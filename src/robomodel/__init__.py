"""robomodel: the ROS robot-modelling workflow as one pip-installable package."""

from robomodel._version import __version__
from robomodel.errors import InputError, RobomodelError

__all__ = ["InputError", "RobomodelError", "__version__"]
