"""Message types built from definitions (robomodel.runtime.msg._resolver) against independent
references: rosbags' CDR serialisation and RIHS01 hashes for every type of its ROS 2 Jazzy
store, Debian's genpy md5sums for ROS 1, and the hand-written classes (a class built from the
definition must give the same bytes and hash as robomodel's own class of that type)."""

from __future__ import annotations

import importlib
import json
import pkgutil
import subprocess
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import robomodel.runtime.msg as msg_package
from robomodel.runtime.msg import (
    Message,
    MessageTypeError,
    _resolver,
    deserialize,
    get_message_type,
    message_from_dict,
    message_to_dict,
    serialize,
)
from robomodel.runtime.msg._from_definition import build_message_class
from robomodel.runtime.msg.schema import message_type_names
from robomodel.runtime.msg.typehash import type_hash
from tests.timing import scaled

typesys = pytest.importorskip("rosbags.typesys")
STORE = typesys.get_typestore(typesys.Stores.ROS2_JAZZY)
NOETIC = typesys.get_typestore(typesys.Stores.ROS1_NOETIC)
BASE, NAME, ARRAY = 1, 2, 3

COMMON = (
    "builtin_interfaces", "diagnostic_msgs", "geometry_msgs", "nav_msgs", "rosgraph_msgs",
    "sensor_msgs", "shape_msgs", "std_msgs", "stereo_msgs", "tf2_msgs", "trajectory_msgs",
    "visualization_msgs", "action_msgs", "unique_identifier_msgs", "lifecycle_msgs",
    "rcl_interfaces", "statistics_msgs", "actionlib_msgs",
)  # fmt: skip
COMMON_TYPES = sorted(n for n in STORE.fielddefs if n.split("/")[0] in COMMON)
# byte is rosidl's octet (0..255) in robomodel, rosbags' CDR packs it signed: the same byte
# on the wire for 0..127, so the value stays in that range.
_INTS = {"int8": -7, "uint8": 200, "byte": 101, "char": 65, "int16": -300, "uint16": 60000,
         "int32": -70000, "uint32": 4000000000, "int64": -(2**40), "uint64": 2**63 + 5}  # fmt: skip
_DTYPES = {"bool": bool, "int8": np.int8, "uint8": np.uint8, "byte": np.uint8, "char": np.uint8,
           "int16": np.int16, "uint16": np.uint16, "int32": np.int32, "uint32": np.uint32,
           "int64": np.int64, "uint64": np.uint64, "float32": np.float32,
           "float64": np.float64}  # fmt: skip


def _has_char(name: str, seen: set[str] | None = None) -> bool:
    """rosbags hashes ``char`` as ROS 1 does; rosidl (and robomodel) as uint8 (see
    tests/runtime/test_type_hashes.py's test_char_is_uint8_as_rosidl_has_it)."""
    seen = set() if seen is None else seen
    if name in seen:
        return False
    seen.add(name)
    for _, desc in STORE.fielddefs[name][1]:
        while desc[0] not in (BASE, NAME):
            desc = desc[1][0]
        if (desc[0] == BASE and desc[1][0] == "char") or (
            desc[0] == NAME and _has_char(desc[1], seen)
        ):
            return True
    return False


def _value(desc: Any, i: int) -> Any:
    """A value of every field that a wrong codec would mangle (signs, high bits, fractions)."""
    kind, rest = desc
    if kind == BASE:
        name, bound = rest
        if name == "string":
            return f"s{i}-é"[: bound or None]
        if name == "bool":
            return i % 2 == 0
        if name in ("float32", "float64"):
            return 1.5 + i
        return _INTS[name]
    if kind == NAME:
        return _dict(rest, i)
    item, size = rest
    count = size if kind == ARRAY else min(2, size or 2)
    return [_value(item, i + k + 1) for k in range(count)]


def _dict(name: str, i: int = 0) -> dict[str, Any]:
    fields = STORE.fielddefs[name][1]
    return {n: _value(d, i + k) for k, (n, d) in enumerate(fields) if not _placeholder(n)}


def _placeholder(name: str) -> bool:
    return name == "structure_needs_at_least_one_member"


def _rosbags(desc: Any, value: Any) -> Any:
    """The same value as rosbags' message classes hold it (numpy arrays for numbers)."""
    kind, rest = desc
    if kind == BASE:
        return value
    if kind == NAME:
        cls = STORE.types[rest]
        args = {n: _rosbags(d, value.get(n)) for n, d in STORE.fielddefs[rest][1]}
        return cls(**{n: (0 if _placeholder(n) else v) for n, v in args.items()})
    item = rest[0]
    if item[0] == BASE and item[1][0] != "string":
        return np.array(value, dtype=_DTYPES[item[1][0]])
    return [_rosbags(item, v) for v in value]


@pytest.mark.parametrize("name", COMMON_TYPES)
def test_round_trip_against_rosbags(name: str) -> None:
    data = _dict(name)
    cls = get_message_type(name)
    msg = message_from_dict(cls, data)
    payload = serialize(msg)
    assert payload == bytes(STORE.serialize_cdr(_rosbags((NAME, name), data), name))
    back = deserialize(payload, cls)
    assert back == msg
    assert json.dumps(message_to_dict(back)) == json.dumps(data)
    if not _has_char(name):
        assert type_hash(cls) == STORE.hash_rihs01(name)


def test_the_store_comparison_is_not_vacuous() -> None:
    assert len(COMMON_TYPES) > 120
    for name in ("sensor_msgs/msg/Image", "visualization_msgs/msg/Marker", "nav_msgs/msg/Path"):
        assert name in COMMON_TYPES
        assert get_message_type(name).__module__.endswith("_from_definition")


def _generated(name: str, cache: dict[str, type[Message]]) -> type[Message]:
    """A class built from the store alone, nested types included (no hand-written class)."""
    if name not in cache:
        cache[name] = build_message_class(
            name, STORE.fielddefs[name], lambda n: _generated(n, cache)
        )
    return cache[name]


for _module in pkgutil.walk_packages(msg_package.__path__, "robomodel.runtime.msg."):
    if not _module.name.rsplit(".", 1)[-1].startswith("_"):
        importlib.import_module(_module.name)
HAND_WRITTEN = [n for n in message_type_names() if n in STORE.fielddefs]


@pytest.mark.parametrize("name", HAND_WRITTEN)
def test_hand_written_equals_generated(name: str) -> None:
    """A hand-written class keeps precedence, and gives the bytes and hash of the class
    generated from rosbags' definition (and rosbags' own bytes)."""
    ours = get_message_type(name)
    assert not ours.__module__.endswith("_from_definition")
    generated = _generated(name, {})
    data = _dict(name)
    payload = serialize(message_from_dict(ours, data))
    assert payload == serialize(message_from_dict(generated, data))
    assert payload == bytes(STORE.serialize_cdr(_rosbags((NAME, name), data), name))
    assert type_hash(ours) == type_hash(generated)


def test_the_hand_written_comparison_is_not_vacuous() -> None:
    assert len(HAND_WRITTEN) > 40
    assert "sensor_msgs/msg/JointState" in HAND_WRITTEN


def test_char_differs_from_rosbags_as_documented() -> None:
    """rosbags hashes a ``char`` field as its own type; rosidl as uint8 (the cited hash of
    service_msgs/msg/ServiceEventInfo in test_type_hashes.py proves rosidl's is on the wire)."""
    cls = get_message_type("std_msgs/msg/Char")
    assert cls.__fields__ == (("data", "char"),)
    assert type_hash(cls) != STORE.hash_rihs01("std_msgs/msg/Char")


def test_unknown_type_is_one_line_naming_where_robomodel_looked(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    monkeypatch.setenv("ROS_PACKAGE_PATH", str(tmp_path))
    _resolver.configure()
    try:
        with pytest.raises(MessageTypeError) as info:
            get_message_type("sensor_msgs/msg/Imag")
    finally:
        monkeypatch.delenv("ROS_PACKAGE_PATH")
        _resolver.configure()
    text = str(info.value)
    assert "\n" not in text
    assert "did you mean sensor_msgs/msg/Image" in text
    assert f"ROS_PACKAGE_PATH {tmp_path}" in text
    assert "ROS 2 jazzy" in text
    assert "std_msgs/msg/String" not in text  # not the list of every known type


def test_an_unknown_type_that_is_caught_costs_no_search_for_close_names(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """The ROS 1 codec asks whether robomodel has a class for each nested type and catches the
    error: the close names (every shipped type module imported, the package path crawled) are
    looked for when the message is read, once, not when the error is raised."""
    searches: list[str] = []
    real_hint = _resolver._hint
    monkeypatch.setattr(_resolver, "_hint", lambda key: searches.append(key) or real_hint(key))
    with pytest.raises(MessageTypeError) as info:
        get_message_type("sensor_msgs/msg/Imag")
    assert searches == []
    assert "did you mean sensor_msgs/msg/Image" in str(info.value)
    assert str(info.value) == str(info.value)
    assert searches == ["sensor_msgs/msg/Imag"]


def test_a_type_missing_from_a_package_robomodel_ships_is_not_looked_for_in_the_ros2_store(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """ROS 1's controller_manager_msgs/HardwareInterfaceResources (which ROS 2's package lacks)
    is asked for by the ROS 1 codec of every list_controllers call: the ROS 2 store, whose
    import is most of such a command's start, has no controller_manager_msgs at all."""
    asked: list[int] = []
    real_store = _resolver._distro_store
    monkeypatch.setattr(_resolver, "_distro_store", lambda: asked.append(1) or real_store())
    with pytest.raises(MessageTypeError):
        get_message_type("controller_manager_msgs/msg/HardwareInterfaceResources")
    assert asked == []
    with pytest.raises(MessageTypeError):  # a package robomodel does not ship: the store is asked
        get_message_type("shape_msgs/msg/NoSuchShape")
    assert asked == [1]


def test_no_ros2_store_has_messages_of_a_package_whose_messages_robomodel_ships() -> None:
    """The rule the resolver skips the ROS 2 store by, checked on every store of the installed
    rosbags."""
    for package in ("controller_manager_msgs", "control_msgs", "gazebo_msgs"):
        assert _resolver._messages_shipped(f"{package}/msg/Any")
    assert not _resolver._messages_shipped("sensor_msgs/msg/Image")  # only its services shipped
    for store in typesys.Stores:
        if store.name.startswith("ROS2"):
            fielddefs = typesys.get_typestore(store).fielddefs
            assert not [key for key in fielddefs if _resolver._messages_shipped(key)], store.name


def test_the_package_path_is_crawled_once_for_its_files_and_robomodel_s_copies(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    indexes: list[object] = []
    real_index = _resolver._index
    monkeypatch.setattr(_resolver, "_index", lambda: indexes.append(1) or real_index())
    caches = (_resolver._package_path_files, _resolver._package_files)
    for cache in caches:
        cache.cache_clear()
    try:
        with_copies = _resolver._package_files()
        package_path_only = _resolver._package_files(shipped=False)
    finally:
        for cache in caches:
            cache.cache_clear()
    assert len(indexes) == 1
    assert "control_msgs/action/FollowJointTrajectory" in with_copies
    assert "control_msgs/action/FollowJointTrajectory" not in package_path_only


def test_distro_from_ros_distro(monkeypatch: pytest.MonkeyPatch) -> None:
    """Jazzy's sensor_msgs/msg/Range has a ``variance`` field that Humble's lacks: ROS_DISTRO
    picks the store, and a ROS 1 distribution name falls back to Jazzy."""
    monkeypatch.setenv("ROS_DISTRO", "humble")
    _resolver.configure()
    try:
        humble = get_message_type("sensor_msgs/msg/Range")
        assert "variance" not in humble.field_names()
        humble_store = typesys.get_typestore(typesys.Stores.ROS2_HUMBLE)
        assert type_hash(humble) == humble_store.hash_rihs01("sensor_msgs/msg/Range")
        assert type_hash(humble) != STORE.hash_rihs01("sensor_msgs/msg/Range")
        monkeypatch.setenv("ROS_DISTRO", "noetic")
        _resolver.configure()
        assert "variance" in get_message_type("sensor_msgs/msg/Range").field_names()
    finally:
        monkeypatch.delenv("ROS_DISTRO")
        _resolver.configure()


def test_ros1_only_names_from_the_noetic_store() -> None:
    cls = get_message_type("actionlib_msgs/msg/GoalID")
    assert [n for n, _ in cls.__fields__] == ["stamp", "id"]


_GENPY = "/usr/bin/python3"
ROS1_TYPES = ["sensor_msgs/Image", "sensor_msgs/PointCloud2", "sensor_msgs/CameraInfo",
              "geometry_msgs/PoseArray", "geometry_msgs/PolygonStamped",
              "rosgraph_msgs/Log", "actionlib_msgs/GoalStatusArray"]  # fmt: skip


def test_ros1_md5sums_equal_genpy_and_rosbags() -> None:
    """md5sums of generated classes' ROS 1 types: Debian's genpy modules and rosbags agree."""
    from robomodel.runtime.transport.ros1.ros1_types import ros1_type

    script = (
        "import importlib, json\nout = {}\n"
        f"for name in {ROS1_TYPES!r}:\n"
        "    pkg, typ = name.split('/')\n"
        "    out[name] = getattr(importlib.import_module(pkg + '.msg'), typ)._md5sum\n"
        "print(json.dumps(out))"
    )
    done = subprocess.run(
        [_GENPY, "-c", script], capture_output=True, text=True, timeout=scaled(60)
    )
    assert done.returncode == 0, done.stderr[-400:]
    genpy = json.loads(done.stdout)
    for name in ROS1_TYPES:
        package, typ = name.split("/")
        key = f"{package}/msg/{typ}"
        ours = ros1_type(get_message_type(key))
        assert ours.md5sum == genpy[name] == NOETIC.generate_msgdef(key, ros_version=1)[1], name


def test_uint8_sequences_out_of_range_are_codec_errors() -> None:
    """uint8[] is packed with bytes() (fast path): a bad value is still a typed error."""
    from robomodel.runtime.msg import CDRError
    from robomodel.runtime.transport.ros1.ros1_types import Ros1CodecError, ros1_type

    image = get_message_type("sensor_msgs/msg/Image")
    for bad in ([256], [-1], ["a"]):
        msg = image(data=bad)  # type: ignore[call-arg]
        with pytest.raises(CDRError, match="does not fit"):
            serialize(msg)
        with pytest.raises(Ros1CodecError, match="does not fit"):
            ros1_type(image).encode(msg)
    good = image(data=[0, 255, 7])  # type: ignore[call-arg]
    held = image(data=b"\x00\xff\x07")  # type: ignore[call-arg]
    assert deserialize(serialize(good), image) == held
    assert ros1_type(image).decode(ros1_type(image).encode(good)) == held


def test_uint8_arrays_decode_as_bytes_from_any_byte_container() -> None:
    """uint8[] and uint8[N] decode as bytes (as rospy gives them), on both wires; encoding
    takes lists, tuples, bytes, bytearray, memoryview, array('B') and numpy uint8 arrays
    alike; int8[] stays a list of ints; YAML input gives the decoded value, YAML output the
    list of ints ``ros2 topic echo`` prints."""
    import array

    import numpy as np

    from robomodel.runtime.msg import message_from_yaml, message_to_yaml
    from robomodel.runtime.msg.types.unique_identifier_msgs import UUID
    from robomodel.runtime.transport.ros1.ros1_types import ros1_type

    image = get_message_type("sensor_msgs/msg/Image")
    values = [0, 255, 7, 128]
    wire = serialize(image(data=values))  # type: ignore[call-arg]
    for data in (tuple(values), bytes(values), bytearray(values), memoryview(bytes(values)),
                 array.array("B", values), np.array(values, dtype=np.uint8)):  # fmt: skip
        msg = image(data=data)  # type: ignore[call-arg]
        assert serialize(msg) == wire, type(data)
        assert type(deserialize(serialize(msg), image).data) is bytes
        assert ros1_type(image).decode(ros1_type(image).encode(msg)).data == bytes(values)
    assert deserialize(serialize(image()), image).data == b""
    assert ros1_type(image).decode(ros1_type(image).encode(image())).data == b""
    uuid = UUID(list(range(16)))
    assert deserialize(serialize(uuid), UUID).uuid == bytes(range(16))
    grid = get_message_type("nav_msgs/msg/OccupancyGrid")
    cells = grid(data=[-1, 0, 100])  # type: ignore[call-arg]
    assert deserialize(serialize(cells), grid).data == [-1, 0, 100]
    parsed = message_from_yaml(image, "{data: [0, 255, 7, 128]}")
    assert parsed == deserialize(wire, image)
    assert message_to_yaml(parsed).endswith("data:\n- 0\n- 255\n- 7\n- 128\n")


def test_topic_pub_shows_uint8_arrays_as_ros2_topic_pub() -> None:
    """rosidl's __repr__ strips array('B', ...): ``publishing #1: ...(data=[0, 255])``."""
    from robomodel.cli.topic import _fields

    image = get_message_type("sensor_msgs/msg/Image")
    assert _fields(image(data=b"\x00\xff")).endswith(", data=[0, 255]")  # type: ignore[call-arg]
