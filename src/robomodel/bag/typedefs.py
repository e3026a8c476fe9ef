"""Message definitions as bags store them, from robomodel's message classes.

rosbag2 keeps, per type, a ``ros2msg`` schema: the type's ``.msg`` fields followed by each
type it uses, each after a line of 80 ``=`` and ``MSG: pkg/Name`` (the layout of rosbag2's
``LocalMessageDefinitionSource`` and of rosbags' ``generate_msgdef``), plus the type's RIHS01
hash. Each type's text is :func:`~robomodel.runtime.msg.definition.message_text`: its constants
and fields (comments and default values of the original ``.msg`` files are not kept by
robomodel's classes), what readers (Foxglove, PlotJuggler, rosbags) decode by.
"""

from __future__ import annotations

from robomodel.runtime.msg import Array, Message, Seq
from robomodel.runtime.msg.definition import message_text, short_name
from robomodel.runtime.msg.schema import Spec
from robomodel.runtime.msg.typehash import type_hash

__all__ = ["rihs01", "ros2msg_definition"]

_SEPARATOR = "=" * 80


def _nested(spec: Spec) -> type[Message] | None:
    while isinstance(spec, Seq | Array):
        spec = spec.item
    return None if isinstance(spec, str) else spec


def ros2msg_definition(cls: type[Message]) -> str:
    """The ``ros2msg`` schema text of ``cls`` with its dependencies, depth first, each once."""
    found = _DEFINITIONS.get(cls)
    if found is None:
        found = _DEFINITIONS[cls] = _definition(cls)
    return found


_DEFINITIONS: dict[type[Message], str] = {}


def _definition(cls: type[Message]) -> str:
    order: list[type[Message]] = []

    def visit(kind: type[Message]) -> None:
        for _, spec in kind.__fields__:
            nested = _nested(spec)
            if nested is not None and nested not in order:
                order.append(nested)
                visit(nested)

    visit(cls)
    parts = [message_text(cls)]
    for dep in order:
        parts.append(f"{_SEPARATOR}\nMSG: {short_name(dep.__typename__)}\n{message_text(dep)}")
    return "".join(parts)


def rihs01(cls: type[Message]) -> str:
    """The type's ``RIHS01_...`` hash (REP 2016), as ROS 2 Jazzy computes it."""
    return type_hash(cls)
