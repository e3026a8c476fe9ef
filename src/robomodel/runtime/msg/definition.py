"""Interface definitions: ``.msg``, ``.srv`` and ``.action`` text parsed into per-type field
definitions, those turned into field specs, and field specs written back as ``.msg`` text.

This is the one parser of the message layer: the offline generator (tools/gen_msgs.py), the
run-time resolver (:mod:`._resolver`) and the bag and type-description writers all use it.

A *field definition* is what rosbags' type system gives per type (``get_types_from_msg``, its
type stores' ``fielddefs``): ``(constants, fields)``, constants as ``(name, type, value)`` and
fields as ``(name, (node type, details))``. rosbags parses the ``.msg`` grammar (relative type
names, ``Header``, bounds, constants, ``===``/``MSG:`` sections); this module splits services
and actions into their messages, names the parts as rosidl does and maps field types onto
robomodel's specs (:mod:`.schema`).
"""

from __future__ import annotations

import itertools
import keyword
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass
from typing import Any, Literal

from robomodel.runtime.msg.schema import (
    PRIMITIVES,
    Array,
    Message,
    MessageTypeError,
    Seq,
    Spec,
)
from robomodel.runtime.msg.spec import (
    ARRAY,
    BASE,
    NAME,
    PLACEHOLDER,
    SEQUENCE,
    FieldDef,
    short_name,
    spec_of,
)

__all__ = [
    "LIMITS",
    "PART_SUFFIXES",
    "PLACEHOLDER",
    "DefinitionLimits",
    "FieldDef",
    "Lookup",
    "check_limits",
    "field_spec",
    "field_specs",
    "message_text",
    "nested_type",
    "parse_interface",
    "parse_message",
    "recursion_in",
    "short_name",
    "split_parts",
]

Lookup = Callable[[str], type[Message]]
Kind = Literal["msg", "srv", "action"]


@dataclass(frozen=True, slots=True)
class DefinitionLimits:
    """Bounds on a definition robomodel builds a class from (docs/reference/limits.md). The
    largest type of a ROS 2 Jazzy or ROS 1 Noetic install has 93 fields and constants
    (type_description_interfaces/msg/FieldType); a definition past a bound is refused in one
    line before a class is built, so a peer cannot make a lookup take minutes."""

    max_fields: int = 1_024  # fields and constants of one type
    max_depth: int = 32  # message types nested in one another
    max_flattened: int = 65_536  # fields once nested types (and fixed arrays of them) are expanded


LIMITS = DefinitionLimits()

# The messages a service or an action file defines, in the file's order (rosidl's names:
# pkg/srv/Name_Request, pkg/action/Name_Goal, ...).
PART_SUFFIXES: dict[Kind, tuple[str, ...]] = {
    "msg": (),
    "srv": ("Request", "Response"),
    "action": ("Goal", "Result", "Feedback"),
}


def split_parts(text: str, kind: Kind, *, where: str) -> tuple[str, ...]:
    """The message definitions of a ``.srv`` (request, response) or ``.action`` (goal, result,
    feedback) file's text, split at its lines ``---`` (rosidl_adapter's
    ``parse_service_string``/``parse_action_string``; trailing blanks are allowed, as genmsg
    allows them)."""
    lines = text.splitlines()
    cuts = [index for index, line in enumerate(lines) if line.rstrip() == "---"]
    wanted = len(PART_SUFFIXES[kind]) - 1
    if len(cuts) != wanted:
        what = (
            "a service needs its request and response split by one line"
            if kind == "srv"
            else "an action needs its goal, result and feedback split by two lines"
        )
        raise MessageTypeError(f"{where}: {what} '---' (found {len(cuts)})")
    bounds = [-1, *cuts, len(lines)]
    return tuple("\n".join(lines[a + 1 : b]) + "\n" for a, b in itertools.pairwise(bounds))


def parse_message(text: str, name: str, *, where: str) -> dict[str, FieldDef]:
    """The field definitions of message ``name`` (``pkg/msg/Name``, or a service or action
    part such as ``pkg/srv/Name_Request``) and of the types its text defines after ``===`` /
    ``MSG:`` lines (a ROS 1 ``message_definition``, a bag's ``ros2msg`` schema).

    rosbags names a parsed type ``pkg/msg/Name`` and resolves relative names in ``pkg``, so a
    part is parsed under that name and renamed.
    """
    from rosbags.typesys import TypesysError, get_types_from_msg

    _count_lines(text, name, where=where)
    package, _, short = name.split("/")
    as_message = f"{package}/msg/{short}"
    try:
        found: dict[str, FieldDef] = dict(get_types_from_msg(text, as_message))
    except TypesysError as exc:
        detail = " ".join(str(exc).split())  # one line: rosbags quotes the text over several
        raise MessageTypeError(f"{where}: not a valid message definition: {detail}") from None
    if as_message != name:
        found[name] = found.pop(as_message)
    return found


def _count_lines(text: str, name: str, *, where: str) -> None:
    """Refuse, before parsing, a text with more field or constant lines in one type's section
    than :data:`LIMITS` allows (rosbags' parser would take seconds per thousand)."""
    count, section = 0, name
    for line in text.splitlines():
        line = line.partition("#")[0].strip()
        if line.startswith("MSG:"):
            count, section = 0, line[4:].strip()
        elif line and line.strip("=") and line != "---":
            count += 1
            if count > LIMITS.max_fields:
                raise MessageTypeError(
                    f"{where}: {section} has more than {LIMITS.max_fields} fields and constants"
                    " (robomodel's bound, docs/reference/limits.md)"
                )


def parse_interface(text: str, key: str, *, where: str) -> dict[str, FieldDef]:
    """The field definitions of every message an interface file defines, by type name:
    ``pkg/msg/Name`` for a ``.msg``; ``pkg/srv/Name_Request`` and ``_Response`` for a ``.srv``;
    ``pkg/action/Name_Goal``, ``_Result`` and ``_Feedback`` for an ``.action``."""
    kind = key.split("/")[1]
    if kind == "msg":
        return {key: parse_message(text, key, where=where)[key]}
    if kind not in ("srv", "action"):
        raise MessageTypeError(f"{where}: '{key}' is not a msg, srv or action type name")
    suffixes = PART_SUFFIXES["srv" if kind == "srv" else "action"]
    parts = split_parts(text, "srv" if kind == "srv" else "action", where=where)
    found: dict[str, FieldDef] = {}
    for suffix, part in zip(suffixes, parts, strict=True):
        name = f"{key}_{suffix}"
        found[name] = parse_message(part, name, where=where)[name]
    return found


def nested_type(desc: Any) -> str | None:
    """The type name a field definition refers to (through arrays), or None for a base type."""
    while int(desc[0]) in (ARRAY, SEQUENCE):
        desc = desc[1][0]
    return str(desc[1]) if int(desc[0]) == NAME else None


def recursion_in(found: Mapping[str, FieldDef]) -> tuple[str, ...] | None:
    """A chain of types of ``found`` that contains itself (``A -> B -> A``), or None.

    ROS message types cannot nest themselves, not even through an array (rosidl and genmsg
    refuse it: a message's size would be unbounded at every level); a definition learned from
    a peer or a file that does is refused before any class or codec recurses through it."""
    done: set[str] = set()

    def children(name: str) -> Iterator[str]:
        for _, desc in found[name][1]:
            nested = nested_type(desc)
            if nested is not None and nested in found:
                yield nested

    for start in found:
        if start in done:
            continue
        # depth-first with an explicit stack: a long chain must not exhaust Python's own
        path, on_path = [start], {start}
        stack = [children(start)]
        while stack:
            child = next(stack[-1], None)
            if child is None:
                stack.pop()
                done.add(path[-1])
                on_path.discard(path.pop())
            elif child in on_path:
                return (*path[path.index(child) :], child)
            elif child not in done:
                path.append(child)
                on_path.add(child)
                stack.append(children(child))
    return None


def check_limits(found: Mapping[str, FieldDef]) -> None:
    """Refuse (MessageTypeError, one line) a set of definitions, free of recursion
    (:func:`recursion_in`), with a type past :data:`LIMITS`: fields and constants, nesting depth
    or flattened size. A type ``found`` does not define counts as one field of depth one."""
    depth: dict[str, int] = {}
    flat: dict[str, int] = {}

    def measure(root: str) -> None:
        # post-order without recursion: a type is measured after every type it uses
        stack = [(root, False)]
        while stack:
            name, ready = stack.pop()
            if name in depth:
                continue
            nested = [(nested_type(desc), desc) for _, desc in found[name][1]]
            inner = [n for n, _ in nested if n is not None and n in found and n not in depth]
            if not ready and inner:
                stack.append((name, True))
                stack += [(n, False) for n in inner]
                continue
            if len(found[name][0]) + len(found[name][1]) > LIMITS.max_fields:
                raise MessageTypeError(f"{name}: more than {LIMITS.max_fields} fields and "
                                       "constants (robomodel's bound, docs/reference/limits.md)")  # fmt: skip
            depth[name] = 1 + max((depth.get(n, 1) for n, _ in nested if n), default=0)
            flat[name] = sum(flat.get(n, 1) * _fixed_count(d) if n else 1 for n, d in nested)
            if depth[name] > LIMITS.max_depth:
                raise MessageTypeError(f"{name}: message types nested more than "
                                       f"{LIMITS.max_depth} deep (robomodel's bound, "
                                       "docs/reference/limits.md)")  # fmt: skip
            if flat[name] > LIMITS.max_flattened:
                raise MessageTypeError(f"{name}: more than {LIMITS.max_flattened} fields once its "
                                       "nested types are expanded (robomodel's bound, "
                                       "docs/reference/limits.md)")  # fmt: skip

    for name in found:
        measure(name)


def _fixed_count(desc: Any) -> int:
    """How many times a field holds its item: the product of its fixed array sizes."""
    count = 1
    while int(desc[0]) in (ARRAY, SEQUENCE):
        if int(desc[0]) == ARRAY:
            count *= max(int(desc[1][1]), 1)
        desc = desc[1][0]
    return count


def field_spec(desc: Any, lookup: Lookup, *, where: str, ros1: bool = False) -> Spec:
    """The robomodel field spec of a field definition ``(node type, details)``.

    ``byte`` is ROS 1's deprecated alias of ``int8`` (genmsg's msgs.py) and ROS 2's ``octet``
    (rosidl_adapter's MSG_TYPE_TO_IDL), hence ``ros1``; ``char`` is ``uint8`` in both and kept as
    ``char``, which the RIHS01 hash and ``.msg`` text tell apart from ``uint8``.

    Args:
        desc: ``(node type, details)`` as in rosbags' ``fielddefs``.
        lookup: Gives the message class of a nested type name (``pkg/msg/Name``).
        where: ``type.field``, for the error message.
        ros1: The definition is a ROS 1 one (rosbags' Noetic store, a ROS 1 package).
    """
    kind, rest = int(desc[0]), desc[1]
    if kind == BASE:
        name, bound = rest
        name = str(name)
        if name in ("octet", "byte"):
            name = "int8" if ros1 and name == "byte" else "byte"
        if name == "string":
            return f"string<={bound}" if bound else "string"
        if name not in PRIMITIVES:
            raise MessageTypeError(f"{where}: robomodel has no codec for the field type '{name}'")
        return name
    if kind == NAME:
        return lookup(str(rest))
    item, size = rest
    inner = field_spec(item, lookup, where=where, ros1=ros1)
    if kind == ARRAY:
        return Array(inner, int(size))
    return Seq(inner, int(size) or None)


def field_specs(
    name: str, definition: FieldDef, lookup: Lookup, *, ros1: bool = False
) -> tuple[tuple[str, Spec], ...]:
    """``(name, spec)`` of every field of type ``name``, rosidl's placeholder left out."""
    fields = definition[1]
    if len(fields) + len(definition[0]) > LIMITS.max_fields:
        raise MessageTypeError(
            f"{name}: more than {LIMITS.max_fields} fields and constants (robomodel's bound,"
            " docs/reference/limits.md)"
        )
    specs: list[tuple[str, Spec]] = []
    for field_name, desc in fields:
        if field_name == PLACEHOLDER and len(fields) == 1:
            break
        if not field_name.isidentifier() or keyword.iskeyword(field_name):
            raise MessageTypeError(f"{name}: field name '{field_name}' is not usable in Python")
        specs.append(
            (field_name, field_spec(desc, lookup, where=f"{name}.{field_name}", ros1=ros1))
        )
    return tuple(specs)


def message_text(cls: type[Message]) -> str:
    """The ``.msg`` text of a message class: its constants, then its fields, one a line
    (without the comments and default values of the original file, which classes do not keep):
    its :class:`~.spec.MessageSpec`'s ``msg``."""
    return spec_of(cls).msg
