"""The description layer: the URDF model, its parser, writer and validation, and ROS packages."""

from robomodel.description.model import *  # noqa: F403
from robomodel.description.model import __all__ as _model_all
from robomodel.description.packages import Package, PackageIndex
from robomodel.description.urdf.reader import ParseResult, URDFWarning, parse_urdf, read_urdf
from robomodel.description.validate import validate, validate_resources

__all__ = [
    *_model_all,
    "Package",
    "PackageIndex",
    "ParseResult",
    "URDFWarning",
    "parse_urdf",
    "read_urdf",
    "validate",
    "validate_resources",
]
