"""A drop-in xacro 2.x processor: the same output as ROS xacro 2.1.1, without ROS.

Example:
    >>> from robomodel import xacro
    >>> doc = xacro.process_file("robot.urdf.xacro", mappings={"prefix": "left_"})
    >>> urdf_text = doc.toprettyxml(indent="  ")
"""

from robomodel.xacro._api import ExpansionResult, XacroDocument, expand, process, process_file
from robomodel.xacro._safe_eval import Limits

__all__ = ["ExpansionResult", "Limits", "XacroDocument", "expand", "process", "process_file"]
