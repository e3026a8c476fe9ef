"""ROS 1 message bytes against rosbags' ROS 1 serializer, in-process, for every type of its
Noetic store that robomodel has: rosbags writes a message with a value in every field that a
wrong codec would mangle (signs, high bits, fractions, non-ASCII text, counts), robomodel
decodes it to those values and encodes it back to the same bytes, with the header's ``seq``
where the encoder is given one. Debian's genpy, the other reference, is in a process of its
own (tests/runtime/test_ros1_messages.py)."""

from __future__ import annotations

import struct
from typing import Any

import numpy as np
import pytest

from robomodel.runtime.msg import MessageTypeError, get_message_type, message_to_dict
from robomodel.runtime.transport.ros1.ros1_codec import Ros1CodecError
from robomodel.runtime.transport.ros1.ros1_types import ros1_type

typesys = pytest.importorskip("rosbags.typesys")
NOETIC = typesys.get_typestore(typesys.Stores.ROS1_NOETIC)
BASE, NAME, ARRAY = 1, 2, 3
_INTS = {"int8": -7, "uint8": 200, "byte": -5, "char": 250, "int16": -300, "uint16": 60000,
         "int32": -70000, "uint32": 4000000000, "int64": -(2**40), "uint64": 2**63 + 5}  # fmt: skip
_DTYPES = {"bool": bool, "int8": np.int8, "uint8": np.uint8, "byte": np.int8, "char": np.uint8,
           "int16": np.int16, "uint16": np.uint16, "int32": np.int32, "uint32": np.uint32,
           "int64": np.int64, "uint64": np.uint64, "float32": np.float32,
           "float64": np.float64}  # fmt: skip


def _ours(name: str) -> Any:
    return ros1_type(get_message_type(name))


def _known(name: str) -> bool:
    """Whether robomodel has a class of type ``name``. Only the class: the codecs are made in
    the tests, after collection, so that tools/mutate.py's mutants reach their generation."""
    try:
        get_message_type(name)
    except MessageTypeError:
        return False
    return True


JOINT_STATE, DISPARITY = "sensor_msgs/msg/JointState", "stereo_msgs/msg/DisparityImage"
TYPES = sorted(n for n in NOETIC.fielddefs if _known(n))


HEADER = "std_msgs/msg/Header"
SEQ = 4_000_000_000


def _value(desc: Any, i: int, depth: int) -> Any:
    kind, rest = desc
    if kind == BASE:
        name, _ = rest
        if name == "string":
            return f"s{i}-é"
        if name == "bool":
            return i % 2 == 0
        if name in ("float32", "float64"):
            return 1.5 + i
        return _INTS[name]
    if kind == NAME:
        return _message(rest, i, depth + 1)
    item, size = rest
    count = size if kind == ARRAY else 2
    values = [_value(item, i + k + 1, depth + 1) for k in range(count)]
    if item[0] == BASE and item[1][0] != "string":
        return np.array(values, dtype=_DTYPES[item[1][0]])
    return values


def _message(name: str, i: int = 0, depth: int = 0) -> Any:
    """rosbags' message ``name`` filled; the ``seq`` of a header is robomodel's only in the
    message's own header (rospy numbers what it publishes), 0 deeper down."""
    if name in ("builtin_interfaces/msg/Time", "builtin_interfaces/msg/Duration"):
        return NOETIC.types[name](sec=1_000_000 + i, nanosec=999_999_000 - i)
    fields = NOETIC.fielddefs[name][1]
    values = {n: _value(d, i + k, depth) for k, (n, d) in enumerate(fields)}
    if name == HEADER:
        values["seq"] = SEQ if depth <= 1 else 0
    return NOETIC.types[name](**values)


@pytest.mark.parametrize("name", TYPES)
def test_rosbags_bytes_decode_and_encode_back_the_same(name: str) -> None:
    theirs = _message(name)
    data = bytes(NOETIC.serialize_ros1(theirs, name))
    kind = _ours(name)
    ours = kind.decode(data)
    headed = name == HEADER or any(d == (NAME, HEADER) for _, d in NOETIC.fielddefs[name][1])
    seq = SEQ if headed else 0
    assert kind.encode(ours, seq) == data
    if seq:  # the seq is the encoder's: robomodel's header has none
        assert kind.encode(ours, 7)[:4] == (7).to_bytes(4, "little")
    # the values, where both name the fields alike
    values = message_to_dict(ours)
    for field, _ in NOETIC.fielddefs[name][1]:
        if field in values and field != "header":
            expected = getattr(theirs, field)
            if isinstance(expected, (int, float, str)):
                assert values[field] == expected, field


def test_the_comparison_is_not_vacuous() -> None:
    assert len(TYPES) > 80
    for name in ("sensor_msgs/msg/JointState", "sensor_msgs/msg/Image",
                 "sensor_msgs/msg/CameraInfo", "stereo_msgs/msg/DisparityImage",
                 "visualization_msgs/msg/MarkerArray", "actionlib_msgs/msg/GoalStatusArray"):  # fmt: skip
        assert name in TYPES


def test_a_field_ros_2_renamed_crosses_under_its_ros_1_name() -> None:
    """CameraInfo's ``D``/``K``/``R``/``P`` and DisparityImage's ``T`` are lower case in ROS 2."""
    data = bytes(NOETIC.serialize_ros1(_message(DISPARITY), DISPARITY))
    image = _ours(DISPARITY).decode(data)
    assert (image.f, image.t) == (3.5, 4.5)  # type: ignore[attr-defined]
    info = _ours("sensor_msgs/msg/CameraInfo").decode(
        bytes(
            NOETIC.serialize_ros1(
                _message("sensor_msgs/msg/CameraInfo"), "sensor_msgs/msg/CameraInfo"
            )
        )
    )
    assert info.d == [6.5, 7.5] and info.k[0] == 7.5  # type: ignore[attr-defined]


def test_refusals_name_the_type_and_the_place() -> None:
    kind = _ours(JOINT_STATE)
    data = bytes(NOETIC.serialize_ros1(_message(JOINT_STATE), JOINT_STATE))
    with pytest.raises(Ros1CodecError) as left:
        kind.decode(data + b"\x01\x02")
    assert str(left.value) == "2 bytes left over after the message"
    with pytest.raises(Ros1CodecError) as cut:
        kind.decode(data[:6])
    assert str(cut.value) == "truncated at byte 0"
    with pytest.raises(Ros1CodecError) as count_cut:
        kind.decode(data[: len(data) - 20][:-1] + b"")
    assert "truncated" in str(count_cut.value) or "overruns" in str(count_cut.value)
    point = _ours("geometry_msgs/msg/Polygon")
    with pytest.raises(Ros1CodecError) as items_cut:
        point.decode(b"\x05\x00\x00\x00" + b"\x00" * 12)
    assert str(items_cut.value) == "truncated at byte 16"
    channel = _ours("sensor_msgs/msg/ChannelFloat32")
    with pytest.raises(Ros1CodecError) as overrun:
        channel.decode(b"\x00\x00\x00\x00\x05\x00\x00\x00" + b"\x00" * 4)
    assert str(overrun.value) == "an array of 5 elements at byte 4 overruns the message"
    with pytest.raises(Ros1CodecError) as short:
        point.decode(b"\x05\x00")
    assert str(short.value) == "truncated at byte 0: an array's length is cut off"
    covariance = _ours("geometry_msgs/msg/PoseWithCovariance")
    msg = covariance.decode(bytes(56 + 36 * 8))
    msg.covariance = [0.0] * 35
    with pytest.raises(Ros1CodecError) as fixed:
        covariance.encode(msg)
    assert str(fixed.value) == "a fixed array needs 36 values, got 35"


def test_fields_robomodel_s_class_lacks_are_written_as_ros_1_s_defaults() -> None:
    """A ROS 1 type with fields robomodel's class of it does not have (a package's newer or
    older definition): they go out as zeros, empty strings and sequences, and fixed arrays of
    zeros, and are dropped when read."""
    from robomodel.runtime.msg._from_definition import make_message_class
    from robomodel.runtime.transport.ros1.ros1_codec import make_codec

    base, name, array, seq = 1, 2, 3, 4
    defs = {
        "pkg/msg/Outer": ([], [
            ("x", (base, ("float64", 0))), ("label", (base, ("string", 0))),
            ("flag", (base, ("bool", 0))), ("n", (base, ("int32", 0))),
            ("pair", (array, ((base, ("int16", 0)), 2))), ("values", (seq, ((base, ("float32", 0)), 0))),
            ("when", (name, "builtin_interfaces/msg/Time")), ("inner", (name, "pkg/msg/Inner")),
            ("inners", (array, ((name, "pkg/msg/Inner"), 2))), ("y", (base, ("float64", 0))),
        ]),
        "pkg/msg/Inner": ([], [("a", (base, ("uint8", 0))), ("b", (base, ("string", 0)))]),
    }  # fmt: skip
    outer = make_message_class("pkg/msg/Outer", (("x", "float64"), ("y", "float64")))
    encode, decode = make_codec(
        "pkg/msg/Outer", defs, lambda key: outer if key == "pkg/msg/Outer" else None,
        lambda type_name, field: None,
    )  # fmt: skip
    data = encode(outer(x=1.5, y=-2.0), 0)  # type: ignore[call-arg]
    zeros = 4 + 1 + 4 + 2 * 2 + 4 + 8 + (1 + 4) + 2 * (1 + 4)
    assert data == struct.pack("<d", 1.5) + bytes(zeros) + struct.pack("<d", -2.0)
    assert decode(data) == outer(x=1.5, y=-2.0)  # type: ignore[call-arg]
    label_and_flag = struct.pack("<I", 2) + b"hi" + b"\x01"
    sent = struct.pack("<d", 1.5) + label_and_flag + bytes(zeros - 5) + struct.pack("<d", -2.0)
    assert decode(sent) == outer(x=1.5, y=-2.0)  # type: ignore[call-arg]


def test_fields_in_another_order_than_the_class_s_are_read_by_name() -> None:
    from robomodel.runtime.msg._from_definition import make_message_class
    from robomodel.runtime.transport.ros1.ros1_codec import make_codec

    defs = {"pkg/msg/Swapped": ([], [("y", (1, ("float64", 0))), ("x", (1, ("float64", 0)))])}
    cls = make_message_class("pkg/msg/Swapped", (("x", "float64"), ("y", "float64")))
    encode, decode = make_codec("pkg/msg/Swapped", defs, lambda key: cls, lambda t, f: None)
    data = struct.pack("<dd", 1.0, 2.0)  # y, then x
    assert decode(data) == cls(x=2.0, y=1.0)  # type: ignore[call-arg]
    assert encode(cls(x=2.0, y=1.0), 0) == data  # type: ignore[call-arg]
