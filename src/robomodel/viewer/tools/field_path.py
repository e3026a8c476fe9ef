"""rqt_plot's field paths: ``/topic/field/sub[index]`` resolved against the known topics.

rqt_plot (rqt_plot/topic_completer + rosplot) names a value by the topic followed by the fields
that lead to it, with ``[n]`` for an element of an array: ``/joint_states/position[0]``,
``/joint1_position_controller/state/process_value``. Topic names contain slashes too, so the
topic is the longest prefix of the path that is a known topic. Only numeric leaves (and bools,
plotted as 0/1) can be plotted.
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from robomodel.errors import RobomodelError, close_matches
from robomodel.runtime.msg import Array, Message, Seq
from robomodel.runtime.msg.schema import PRIMITIVES, Spec

__all__ = ["FieldPath", "FieldPathError", "field_value", "resolve_field_path", "set_field"]

_SEGMENT = re.compile(r"^([A-Za-z_][A-Za-z0-9_]*)((?:\[\d+\])*)$")
_INDEX = re.compile(r"\[(\d+)\]")

Step = str | int


class FieldPathError(RobomodelError):
    """A field path that names no topic, no field, or a value that is not a number."""


@dataclass(frozen=True, slots=True)
class FieldPath:
    """A resolved path: the topic, its message type and the steps (field names and indices)."""

    topic: str
    msg_type: type[Message]
    steps: tuple[Step, ...]

    @property
    def text(self) -> str:
        out = self.topic
        for step in self.steps:
            out += f"[{step}]" if isinstance(step, int) else f"/{step}"
        return out


def parse_steps(text: str) -> tuple[Step, ...]:
    """``a/b[2]/c`` (or ``a.b[2].c``) as ``("a", "b", 2, "c")``."""
    steps: list[Step] = []
    for part in re.split(r"[/.]", text.strip().strip("/")):
        if not part:
            continue
        match = _SEGMENT.match(part)
        if match is None:
            raise FieldPathError(f"'{part}' is not a field name (with optional [index])")
        steps.append(match.group(1))
        steps.extend(int(i) for i in _INDEX.findall(match.group(2)))
    return tuple(steps)


def _leaf_spec(msg_type: type[Message], steps: tuple[Step, ...], where: str) -> Spec:
    spec: Spec = msg_type
    for step in steps:
        if isinstance(step, int):
            if not isinstance(spec, (Seq, Array)):
                raise FieldPathError(f"{where}: [{step}] indexes a field that is not an array")
            if isinstance(spec, Array) and step >= spec.size:
                raise FieldPathError(f"{where}: index {step} is past the array's {spec.size}")
            spec = spec.item
            continue
        if isinstance(spec, (Seq, Array)):
            raise FieldPathError(f"{where}: give an index before '{step}' (an array)")
        if isinstance(spec, str):
            raise FieldPathError(f"{where}: '{step}' follows a {spec}, which has no fields")
        fields = dict(spec.__fields__)
        if step not in fields:
            hint = close_matches(step, fields)
            extra = f" (did you mean {', '.join(hint)}?)" if hint else ""
            raise FieldPathError(
                f"{where}: {spec.__typename__} has no field '{step}'{extra}; "
                f"its fields are: {', '.join(fields)}"
            )
        spec = fields[step]
    return spec


def _check_numeric(spec: Spec, where: str) -> None:
    if isinstance(spec, (Seq, Array)):
        raise FieldPathError(f"{where} is an array; add an index, e.g. {where}[0]")
    if not isinstance(spec, str):
        names = ", ".join(spec.field_names())
        raise FieldPathError(f"{where} is a {spec.__typename__}; add one of its fields: {names}")
    if spec == "string":
        raise FieldPathError(f"{where} is a string, which cannot be plotted")
    assert spec in PRIMITIVES


def resolve_field_path(text: str, topics: Mapping[str, type[Message]]) -> FieldPath:
    """Split ``text`` into the longest known topic and a path to a number in its messages.

    Args:
        text: The path as typed (``/odom/pose/pose/position/x``).
        topics: Known topics and their message types.

    Raises:
        FieldPathError: No topic prefixes ``text``, a field does not exist, or the value is not
            numeric; the message names what is valid instead.
    """
    path = "/" + text.strip().strip("/")
    parts = path.strip("/").split("/")
    for k in range(len(parts), 0, -1):
        topic = "/" + "/".join(parts[:k])
        if topic in topics:
            msg_type = topics[topic]
            steps = parse_steps("/".join(parts[k:]))
            if not steps:
                raise FieldPathError(
                    f"{path}: add a field of {msg_type.__typename__} "
                    f"({', '.join(msg_type.field_names())})"
                )
            spec = _leaf_spec(msg_type, steps, path)
            _check_numeric(spec, path)
            return FieldPath(topic, msg_type, steps)
    hint = close_matches(path, topics)
    extra = f" (did you mean {', '.join(hint)}?)" if hint else ""
    raise FieldPathError(
        f"{path}: no known topic is a prefix of it{extra}; topics are: "
        f"{', '.join(sorted(topics)) or '(none yet)'}"
    )


def field_value(msg: Message, steps: tuple[Step, ...]) -> float | None:
    """The number at ``steps`` in ``msg``; None when an array is too short in this message."""
    value: Any = msg
    for step in steps:
        if isinstance(step, int):
            if step >= len(value):
                return None
            value = value[step]
        else:
            value = getattr(value, step)
    return float(value)


def set_field(msg_type: type[Message], steps: tuple[Step, ...], value: float) -> Message:
    """A default ``msg_type`` message with the number at ``steps`` set to ``value``.

    Unbounded arrays are grown with zeros up to the index; integer fields get the value rounded.
    """
    spec = _leaf_spec(msg_type, steps, "/".join(str(s) for s in steps))
    _check_numeric(spec, "/".join(str(s) for s in steps))
    msg = msg_type()
    holder: Any = msg
    specs: Spec = msg_type
    for n, step in enumerate(steps):
        last = n == len(steps) - 1
        if isinstance(step, int):
            assert isinstance(specs, (Seq, Array))
            while len(holder) <= step:
                holder.append(_zero(specs.item))
            specs = specs.item
            if last:
                cast = _cast(specs, value)
                if isinstance(holder, bytearray) and not 0 <= cast <= 255:
                    raise FieldPathError(f"{value} is out of range for {specs} [0, 255]")
                holder[step] = cast
            else:
                holder = holder[step]
        else:
            assert not isinstance(specs, (str, Seq, Array))
            specs = dict(specs.__fields__)[step]
            if last:
                setattr(holder, step, _cast(specs, value))
            else:
                child = getattr(holder, step)
                if isinstance(child, bytes):  # uint8[] is held as bytes: written as a bytearray
                    child = bytearray(child)
                    setattr(holder, step, child)
                holder = child
    return msg


def _zero(spec: Spec) -> Any:
    from robomodel.runtime.msg.schema import default_for

    return default_for(spec)


def _cast(spec: Spec, value: float) -> Any:
    if spec == "bool":
        return bool(value)
    if spec in ("float32", "float64"):
        return float(value)
    return round(value)
