"""MessageSpec (robomodel.runtime.msg.spec) against rosbags' type stores, which generate message
definitions, md5sums and RIHS01 hashes independently of robomodel: every type of the ROS 1
Noetic and ROS 2 Jazzy stores, built from the stores' definitions and (for Jazzy) from the
classes robomodel resolves, gives rosbags' texts and hashes."""

from __future__ import annotations

import dataclasses
from typing import Any

import pytest

from robomodel.runtime.msg import MessageTypeError, get_message_type
from robomodel.runtime.msg.definition import message_text
from robomodel.runtime.msg.spec import (
    Container,
    FieldSpec,
    MessageSpec,
    spec_from_definitions,
    spec_of,
)
from robomodel.runtime.msg.typehash import type_hash

typesys = pytest.importorskip("rosbags.typesys")
NOETIC = typesys.get_typestore(typesys.Stores.ROS1_NOETIC)
JAZZY = typesys.get_typestore(typesys.Stores.ROS2_JAZZY)
BASE, NAME = 1, 2


def _uses_char(store: Any, name: str, seen: set[str] | None = None) -> bool:
    """rosbags hashes ``char`` as a type of its own; rosidl (and robomodel) as uint8 (see
    test_type_hashes.py's test_char_is_uint8_as_rosidl_has_it)."""
    seen = set() if seen is None else seen
    seen.add(name)
    for _, desc in store.fielddefs[name][1]:
        while int(desc[0]) not in (BASE, NAME):
            desc = desc[1][0]
        if int(desc[0]) == BASE and desc[1][0] == "char":
            return True
        if int(desc[0]) == NAME and desc[1] not in seen and _uses_char(store, desc[1], seen):
            return True
    return False


NOETIC_TYPES = sorted(NOETIC.fielddefs)
JAZZY_TYPES = sorted(JAZZY.fielddefs)


def test_the_store_comparisons_are_not_vacuous() -> None:
    assert len(NOETIC_TYPES) > 150 and len(JAZZY_TYPES) > 150
    for name in (
        "sensor_msgs/msg/Image",
        "visualization_msgs/msg/MarkerArray",
        "nav_msgs/msg/Odometry",
    ):
        assert name in NOETIC_TYPES and name in JAZZY_TYPES
    assert (
        sum(bool(spec_from_definitions(n, NOETIC.fielddefs).constants) for n in NOETIC_TYPES) > 15
    )


def test_every_noetic_type_has_rosbags_message_definition_and_md5() -> None:
    """ROS 1: TCPROS's and ROS 1 bags' ``message_definition`` and md5sum (genmsg's algorithm,
    time and duration primitives, message arrays hashed without brackets)."""
    cache: dict[str, MessageSpec] = {}
    for name in NOETIC_TYPES:
        spec = spec_from_definitions(name, NOETIC.fielddefs, cache=cache)
        definition, md5 = NOETIC.generate_msgdef(name, ros_version=1)
        assert (spec.ros1_definition, spec.md5) == (definition, md5), name


def test_every_jazzy_type_has_rosbags_definitions_and_hashes() -> None:
    """ROS 2: the ``ros2msg`` schema, RIHS01, and the ROS 1 dialect of the same definitions."""
    cache: dict[str, MessageSpec] = {}
    checked = 0
    for name in JAZZY_TYPES:
        spec = spec_from_definitions(name, JAZZY.fielddefs, cache=cache)
        assert spec.definition == JAZZY.generate_msgdef(name, ros_version=2)[0], name
        assert (spec.ros1_definition, spec.md5) == JAZZY.generate_msgdef(name, ros_version=1)
        if not _uses_char(JAZZY, name):
            assert spec.rihs01 == JAZZY.hash_rihs01(name), name
            checked += 1
    assert checked > 150


@pytest.mark.parametrize("name", JAZZY_TYPES)
def test_the_class_of_every_jazzy_type_has_the_stores_spec(name: str) -> None:
    """The class robomodel resolves (its own generated one, or one built from a definition)
    has the spec of the store's definition: the same fields, constants, nested types, texts."""
    cls = get_message_type(name)
    ours, theirs = spec_of(cls), spec_from_definitions(name, JAZZY.fielddefs)
    assert ours == theirs
    assert ours.definition == JAZZY.generate_msgdef(name, ros_version=2)[0]
    assert ours.md5 == JAZZY.generate_msgdef(name, ros_version=1)[1]
    assert type_hash(cls) == ours.rihs01
    assert message_text(cls) == ours.msg
    assert spec_of(cls) is ours  # cached per class


def test_nested_types_in_order_of_first_use_each_once() -> None:
    spec = spec_of(get_message_type("nav_msgs/msg/Odometry"))
    assert [dep.name for dep in spec.nested] == [
        "std_msgs/msg/Header",
        "builtin_interfaces/msg/Time",
        "geometry_msgs/msg/PoseWithCovariance",
        "geometry_msgs/msg/Pose",
        "geometry_msgs/msg/Point",
        "geometry_msgs/msg/Quaternion",
        "geometry_msgs/msg/TwistWithCovariance",
        "geometry_msgs/msg/Twist",
        "geometry_msgs/msg/Vector3",
    ]
    assert spec.dependency("geometry_msgs/msg/Twist").fields[0] == FieldSpec(
        "linear", "geometry_msgs/msg/Vector3", nested=True
    )
    # ROS 1 has time as a primitive: no section for it in the message_definition
    assert "MSG: builtin_interfaces/Time" in spec.definition
    assert "MSG: builtin_interfaces/Time" not in spec.ros1_definition
    assert spec.ros1_msg.startswith("std_msgs/Header header\n")


def test_a_changed_field_changes_every_hash() -> None:
    """Two specs of the same name whose fields differ anywhere in the tree differ in md5 and
    RIHS01, as ROS refuses a peer whose definition differs."""
    base = spec_from_definitions("geometry_msgs/msg/PoseStamped", JAZZY.fielddefs)
    point = base.dependency("geometry_msgs/msg/Point")
    wider = dataclasses.replace(
        point, fields=(*point.fields[:2], FieldSpec("z", "float32")), nested=()
    )
    pose = base.dependency("geometry_msgs/msg/Pose")
    pose2 = dataclasses.replace(
        pose, nested=(wider, *(d for d in pose.nested if d.name != point.name))
    )
    changed = dataclasses.replace(
        base,
        nested=tuple(
            pose2 if d.name == pose.name else wider if d is point else d for d in base.nested
        ),
    )
    assert changed != base
    assert changed.md5 != base.md5 and changed.rihs01 != base.rihs01
    assert changed.definition != base.definition


def test_containers_as_msg_text_and_field_type_ids() -> None:
    spec = spec_from_definitions("sensor_msgs/msg/JointState", JAZZY.fielddefs)
    assert spec.fields[1] == FieldSpec("name", "string", container=Container.SEQUENCE)
    assert spec.msg == "std_msgs/Header header\nstring[] name\nfloat64[] position\n" \
        "float64[] velocity\nfloat64[] effort\n"  # fmt: skip
    description = spec.individual_description()["fields"]
    assert [f["type"]["type_id"] for f in description] == [1, 161, 155, 155, 155]


def test_a_definition_that_nests_itself_is_refused() -> None:
    defs = {
        "evil_msgs/msg/A": ((), [("b", (NAME, "evil_msgs/msg/B"))]),
        "evil_msgs/msg/B": ((), [("a", (3, ((NAME, "evil_msgs/msg/A"), 2)))]),
    }
    with pytest.raises(MessageTypeError, match="contains itself"):
        spec_from_definitions("evil_msgs/msg/A", defs)
    with pytest.raises(MessageTypeError, match="no definition of the type std_msgs/msg/Nope"):
        spec_from_definitions("std_msgs/msg/Nope", {})
