"""Interface definitions for the zenoh-ros2-sdk process of the wire tests, from sources
independent of robomodel: the SDK reads ``.msg`` / ``.srv`` files and computes every type
hash itself, so what it is given must not come from robomodel's classes.

- ``interfaces/<pkg>/{msg,srv}/`` and ``custom_interfaces/``: upstream files (``interfaces/README.md`` says from which
  repository, branch and commit), with relative type names qualified by their package;
- any other message: rosbags' Jazzy type store (``get_typestore(Stores.ROS2_JAZZY)``), its
  parsed definition written back as ``.msg`` text (rosbags parses the upstream files itself).

Messages that a written file uses are written too, recursively.
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import Any

__all__ = ["write_definitions"]

UPSTREAM = Path(__file__).with_name("interfaces")
CUSTOM = Path(__file__).with_name("custom_interfaces")  # types robomodel has no class of
_PRIMITIVES = frozenset(
    [
        "bool",
        "byte",
        "char",
        "float32",
        "float64",
        "int8",
        "uint8",
        "int16",
        "uint16",
        "int32",
        "uint32",
        "int64",
        "uint64",
        "string",
        "wstring",
    ]
)


def _store() -> Any:
    from rosbags.typesys import Stores, get_typestore

    return get_typestore(Stores.ROS2_JAZZY)


def _field_type(desc: Any) -> str:
    from rosbags.typesys.base import Nodetype

    kind, rest = desc
    if kind == Nodetype.BASE:
        name, bound = rest
        return f"{name}<={bound}" if bound else str(name)
    if kind == Nodetype.NAME:
        package, _, name = str(rest).split("/")
        return f"{package}/{name}"
    inner = _field_type(rest[0])
    if kind == Nodetype.ARRAY:
        return f"{inner}[{rest[1]}]"
    return f"{inner}[<={rest[1]}]" if rest[1] else f"{inner}[]"


def _from_store(store: Any, name: str) -> str:
    constants, fields = store.fielddefs[name]
    lines = [f"{ctype} {cname}={value}" for cname, ctype, value in constants]
    lines += [f"{_field_type(desc)} {field}" for field, desc in fields]
    return "".join(f"{line}\n" for line in lines)


def _used(text: str, package: str) -> set[str]:
    """The message types (``pkg/msg/Name``) that ``.msg``/``.srv`` text uses."""
    used = set()
    for line in text.splitlines():
        line = line.split("#", 1)[0].strip()
        if not line or line.startswith("---"):
            continue
        base = re.split(r"[\[<]", line.split()[0], maxsplit=1)[0]
        if base in _PRIMITIVES or base in ("time", "duration"):
            continue
        owner, _, name = base.rpartition("/")
        used.add(f"{owner or package}/msg/{name}")
    return used


def _qualified(text: str, package: str) -> str:
    """Relative type names (``ParameterValue[] values``) as rosidl resolves them, in the
    package's own ``msg/`` (``rcl_interfaces/ParameterValue``): the SDK resolves none."""
    lines = []
    for line in text.splitlines():
        words = line.split(None, 1)
        base = re.split(r"[\[<]", words[0], maxsplit=1)[0] if words else ""
        relative = base and base[0].isupper() and "/" not in base and not line.startswith("#")
        owner = "std_msgs" if base == "Header" else package  # rosidl's one special name
        lines.append(f"{owner}/{line.lstrip()}" if relative else line)
    return "".join(f"{line}\n" for line in lines)


def write_definitions(root: Path, names: list[str]) -> Path:
    """Write the types ``names`` (``pkg/msg/Name`` or ``pkg/srv/Name``) and every message they
    use under ``root/<pkg>/{msg,srv}/``."""
    store = _store()
    pending, done = list(names), set()
    while pending:
        name = pending.pop()
        if name in done:
            continue
        done.add(name)
        package, kind, short = name.split("/")
        target = root / package / kind / f"{short}.{kind}"
        target.parent.mkdir(parents=True, exist_ok=True)
        upstream = UPSTREAM / package / kind / f"{short}.{kind}"
        if not upstream.exists():
            upstream = CUSTOM / package / kind / f"{short}.{kind}"
        if upstream.exists():
            target.write_text(_qualified(upstream.read_text(), package))
        elif kind == "msg" and name in store.fielddefs:
            target.write_text(_from_store(store, name))
        else:
            raise LookupError(f"no independent definition of {name} (add it to {UPSTREAM})")
        pending.extend(_used(target.read_text(), package) - done)
    return root
