"""``robomodel view``: RViz's RobotModel and TF displays and joint_state_publisher_gui in a browser.

Importing this package is cheap: viser is imported when a viewer starts, trimesh when it first
loads a mesh file or draws a marker's shape (a missing one raises
:class:`~robomodel.errors.MissingDependencyError` naming the ``viewer`` extra).
"""

from robomodel.viewer.app import Viewer, ViewerOptions
from robomodel.viewer.errors import MeshLoadError, PortInUseError, ViewerError
from robomodel.viewer.scenery import SceneryShape
from robomodel.viewer.session import RobotSource

__all__ = [
    "MeshLoadError",
    "PortInUseError",
    "RobotSource",
    "SceneryShape",
    "Viewer",
    "ViewerError",
    "ViewerOptions",
]
