"""robomodel's classes of control_msgs, controller_manager_msgs, gazebo_msgs and
ros_gz_interfaces have the fields of their upstream ``.msg``/``.srv``/``.action`` files
(``interfaces/``, Jazzy branches) and the RIHS01 hashes rosbags computes from those files.

A field missing, added or of another type changes the type hash, and a real ROS 2 node's
controller manager, JTC action or simulator service would then not match robomodel's.
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import Any

import pytest

from robomodel.runtime.msg.action import make_action  # noqa: F401  (the actions' module)
from robomodel.runtime.msg.schema import (
    Array,
    Message,
    Seq,
    Spec,
    get_message_type,
    get_service_type,
)
from robomodel.runtime.msg.typehash import type_hash

typesys = pytest.importorskip("rosbags.typesys")
Nodetype = pytest.importorskip("rosbags.typesys.base").Nodetype

ROOT = Path(__file__).parent / "interfaces"
SECTIONS = {
    "msg": ("",),
    "srv": ("_Request", "_Response"),
    "action": ("_Goal", "_Result", "_Feedback"),
}


def _definitions() -> dict[str, Any]:
    """Every type of ``interfaces/`` as rosbags parses it (srv and action split at ``---``)."""
    types: dict[str, Any] = {}
    for path in sorted(ROOT.glob("*/*/*")):
        package, kind = path.parent.parent.name, path.parent.name
        parts = re.split(r"^---[ \t]*$", path.read_text(), flags=re.MULTILINE)
        for suffix, text in zip(SECTIONS[kind], parts, strict=True):
            # parsed as a msg so that relative names resolve to the package's msg/, as rosidl
            # resolves them, then named as the section it is
            parsed = typesys.get_types_from_msg(text, f"{package}/msg/{path.stem}{suffix}")
            types[f"{package}/{kind}/{path.stem}{suffix}"] = parsed.popitem()[1]
    return types


DEFINITIONS = _definitions()
STORE = typesys.get_typestore(typesys.Stores.ROS2_JAZZY)
STORE.register(DEFINITIONS)


def _theirs(desc: Any) -> str:
    kind, rest = desc
    if kind == Nodetype.BASE:
        name, bound = rest
        return f"string<={bound}" if bound else name
    if kind == Nodetype.NAME:
        return str(rest)
    inner = _theirs(rest[0])
    if kind == Nodetype.ARRAY:
        return f"{inner}[{rest[1]}]"
    return f"{inner}[<={rest[1]}]" if rest[1] else f"{inner}[]"


def _ours(spec: Spec) -> str:
    if isinstance(spec, str):
        return spec
    if isinstance(spec, Array):
        return f"{_ours(spec.item)}[{spec.size}]"
    if isinstance(spec, Seq):
        inner = _ours(spec.item)
        return f"{inner}[<={spec.bound}]" if spec.bound else f"{inner}[]"
    return spec.__typename__


def _class(name: str) -> type[Message]:
    package, kind, rest = name.split("/")
    if kind == "msg":
        return get_message_type(name)
    if kind == "srv":
        service, _, part = rest.rpartition("_")
        return getattr(get_service_type(f"{package}/srv/{service}"), part)  # type: ignore[no-any-return]
    return get_message_type(name)  # the action's Goal/Result/Feedback are registered messages


def test_every_vendored_definition_is_read() -> None:
    assert len(DEFINITIONS) >= 60
    assert "control_msgs/action/FollowJointTrajectory_Goal" in DEFINITIONS
    assert "controller_manager_msgs/srv/SwitchController_Request" in DEFINITIONS


@pytest.mark.parametrize("name", sorted(DEFINITIONS))
def test_fields_and_hash_match_upstream(name: str) -> None:
    kind = _class(name)
    _, fields = DEFINITIONS[name]
    assert [(n, _ours(s)) for n, s in kind.__fields__] == [(n, _theirs(d)) for n, d in fields]
    assert type_hash(kind) == STORE.hash_rihs01(name)
