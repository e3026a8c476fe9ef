"""Message definitions as bags store them, from robomodel's message classes.

rosbag2 keeps, per type, a ``ros2msg`` schema: the type's ``.msg`` fields followed by each
type it uses, each after a line of 80 ``=`` and ``MSG: pkg/Name`` (the layout of rosbag2's
``LocalMessageDefinitionSource`` and of rosbags' ``generate_msgdef``), plus the type's RIHS01
hash. Both are the class's :class:`~robomodel.runtime.msg.spec.MessageSpec`'s: its constants
and fields (comments and default values of the original ``.msg`` files are not kept by
robomodel's classes), what readers (Foxglove, PlotJuggler, rosbags) decode by.
"""

from __future__ import annotations

from robomodel.runtime.msg import Message
from robomodel.runtime.msg.spec import spec_of

__all__ = ["rihs01", "ros2msg_definition"]


def ros2msg_definition(cls: type[Message]) -> str:
    """The ``ros2msg`` schema text of ``cls`` with its dependencies, depth first, each once."""
    return spec_of(cls).definition


def rihs01(cls: type[Message]) -> str:
    """The type's ``RIHS01_...`` hash (REP 2016), as ROS 2 Jazzy computes it."""
    return spec_of(cls).rihs01
