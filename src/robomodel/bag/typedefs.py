"""Message definitions as bags store them, from robomodel's message classes.

rosbag2 keeps, per type, a ``ros2msg`` schema: the type's ``.msg`` fields followed by each
type it uses, each after a line of 80 ``=`` and ``MSG: pkg/Name`` (the layout of rosbag2's
``LocalMessageDefinitionSource`` and of rosbags' ``generate_msgdef``), plus the type's RIHS01
hash. Constants and comments of the original ``.msg`` files are not kept by robomodel's
classes, so schemas carry fields only: what readers (Foxglove, PlotJuggler, rosbags) decode by.
"""

from __future__ import annotations

from robomodel.runtime.msg import Array, Message, Seq
from robomodel.runtime.msg.schema import Spec
from robomodel.runtime.msg.typehash import type_hash

__all__ = ["rihs01", "ros2msg_definition"]

_SEPARATOR = "=" * 80


def _short(typename: str) -> str:
    """``geometry_msgs/msg/Vector3`` -> ``geometry_msgs/Vector3``, as ``.msg`` files say it.

    The parts of an action or a service (``pkg/action/Name_Feedback``) keep their full name:
    no ``.msg`` file names them, and ``pkg/Name_Feedback`` would be read back as a message of
    another name (and RIHS01 hash)."""
    package, kind, name = typename.split("/")
    return f"{package}/{name}" if kind == "msg" else typename


def _spec_text(spec: Spec) -> tuple[str, str]:
    """(type text, array suffix) of a field spec: ``float64``, ``[]``; ``pkg/T``, ``[3]``."""
    if isinstance(spec, Seq):
        item, _ = _spec_text(spec.item)
        return item, "[]" if spec.bound is None else f"[<={spec.bound}]"
    if isinstance(spec, Array):
        item, _ = _spec_text(spec.item)
        return item, f"[{spec.size}]"
    if isinstance(spec, str):
        return spec, ""
    return _short(spec.__typename__), ""


def _nested(spec: Spec) -> type[Message] | None:
    while isinstance(spec, Seq | Array):
        spec = spec.item
    return None if isinstance(spec, str) else spec


def _fields_text(cls: type[Message]) -> str:
    # constants first, as rosidl's and rosbags' definitions give them
    lines = [f"{c_type} {c_name}={value}" for c_name, c_type, value in cls.__constants__]
    for name, spec in cls.__fields__:
        kind, suffix = _spec_text(spec)
        lines.append(f"{kind}{suffix} {name}")
    return "".join(line + "\n" for line in lines)


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
    parts = [_fields_text(cls)]
    for dep in order:
        parts.append(f"{_SEPARATOR}\nMSG: {_short(dep.__typename__)}\n{_fields_text(dep)}")
    return "".join(parts)


def rihs01(cls: type[Message]) -> str:
    """The type's ``RIHS01_...`` hash (REP 2016), as ROS 2 Jazzy computes it."""
    return type_hash(cls)
