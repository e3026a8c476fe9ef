"""Messages: CDR bytes checked against pycdr2 (an independent implementation), YAML, registry.

No ``from __future__ import annotations`` here: pycdr2 reads the real annotation objects.
"""

import dataclasses
import math
import struct

import numpy as np
import pycdr2
import pytest
from hypothesis import given
from hypothesis import strategies as st
from pycdr2.types import array, float32, float64, int8, int16, int32, sequence, uint8, uint32

from robomodel.runtime import msg as m

# --- independent definitions of the same types with pycdr2 (cyclonedds' Python CDR) --------


@dataclasses.dataclass
class RefTime(pycdr2.IdlStruct, typename="builtin_interfaces/msg/Time"):
    sec: int32
    nanosec: uint32


@dataclasses.dataclass
class RefHeader(pycdr2.IdlStruct, typename="std_msgs/msg/Header"):
    stamp: RefTime
    frame_id: str


@dataclasses.dataclass
class RefJointState(pycdr2.IdlStruct, typename="sensor_msgs/msg/JointState"):
    header: RefHeader
    name: sequence[str]
    position: sequence[float64]
    velocity: sequence[float64]
    effort: sequence[float64]


@dataclasses.dataclass
class RefVector3(pycdr2.IdlStruct, typename="geometry_msgs/msg/Vector3"):
    x: float64
    y: float64
    z: float64


@dataclasses.dataclass
class RefQuaternion(pycdr2.IdlStruct, typename="geometry_msgs/msg/Quaternion"):
    x: float64
    y: float64
    z: float64
    w: float64


@dataclasses.dataclass
class RefTransformStamped(pycdr2.IdlStruct, typename="geometry_msgs/msg/TransformStamped"):
    header: RefHeader
    child_frame_id: str
    translation: RefVector3
    rotation: RefQuaternion


@dataclasses.dataclass
class RefTFMessage(pycdr2.IdlStruct, typename="tf2_msgs/msg/TFMessage"):
    transforms: sequence[RefTransformStamped]


@dataclasses.dataclass
class RefLaserScan(pycdr2.IdlStruct, typename="sensor_msgs/msg/LaserScan"):
    header: RefHeader
    angle_min: float32
    angle_max: float32
    angle_increment: float32
    time_increment: float32
    scan_time: float32
    range_min: float32
    range_max: float32
    ranges: sequence[float32]
    intensities: sequence[float32]


@dataclasses.dataclass
class RefPoseCov(pycdr2.IdlStruct, typename="geometry_msgs/msg/PoseWithCovariance"):
    position: RefVector3
    orientation: RefQuaternion
    covariance: array[float64, 36]


@dataclasses.dataclass
class RefTwistCov(pycdr2.IdlStruct, typename="geometry_msgs/msg/TwistWithCovariance"):
    linear: RefVector3
    angular: RefVector3
    covariance: array[float64, 36]


@dataclasses.dataclass
class RefOdometry(pycdr2.IdlStruct, typename="nav_msgs/msg/Odometry"):
    header: RefHeader
    child_frame_id: str
    pose: RefPoseCov
    twist: RefTwistCov


@dataclasses.dataclass
class RefDuration(pycdr2.IdlStruct, typename="builtin_interfaces/msg/Duration"):
    sec: int32
    nanosec: uint32


@dataclasses.dataclass
class RefPoint(pycdr2.IdlStruct, typename="trajectory_msgs/msg/JointTrajectoryPoint"):
    positions: sequence[float64]
    velocities: sequence[float64]
    accelerations: sequence[float64]
    effort: sequence[float64]
    time_from_start: RefDuration


@dataclasses.dataclass
class RefTransform(pycdr2.IdlStruct, typename="geometry_msgs/msg/Transform"):
    translation: RefVector3
    rotation: RefQuaternion


@dataclasses.dataclass
class RefTwist(pycdr2.IdlStruct, typename="geometry_msgs/msg/Twist"):
    linear: RefVector3
    angular: RefVector3


@dataclasses.dataclass
class RefMultiPoint(pycdr2.IdlStruct, typename="trajectory_msgs/msg/MultiDOFJointTrajectoryPoint"):
    transforms: sequence[RefTransform]
    velocities: sequence[RefTwist]
    accelerations: sequence[RefTwist]
    time_from_start: RefDuration


@dataclasses.dataclass
class RefJTCState(pycdr2.IdlStruct, typename="control_msgs/msg/JointTrajectoryControllerState"):
    header: RefHeader
    joint_names: sequence[str]
    reference: RefPoint
    feedback: RefPoint
    error: RefPoint
    output: RefPoint
    multi_dof_joint_names: sequence[str]
    multi_dof_reference: RefMultiPoint
    multi_dof_feedback: RefMultiPoint
    multi_dof_error: RefMultiPoint
    multi_dof_output: RefMultiPoint
    speed_scaling_factor: float64


names = st.text(alphabet=st.characters(min_codepoint=32, max_codepoint=0x2FF), max_size=12)
floats = st.floats(allow_nan=False, width=64)
stamps = st.tuples(st.integers(-(2**31), 2**31 - 1), st.integers(0, 2**32 - 1))


@given(
    stamps,
    names,
    st.lists(names, max_size=5),
    st.lists(floats, max_size=5),
    st.lists(floats, max_size=3),
)
def test_joint_state_bytes_match_pycdr2(stamp, frame, joint_names, positions, efforts) -> None:  # type: ignore[no-untyped-def]
    ours = m.JointState(m.Header(m.Time(*stamp), frame), joint_names, positions, [], efforts)
    ref = RefJointState(RefHeader(RefTime(*stamp), frame), joint_names, positions, [], efforts)
    assert m.serialize(ours) == ref.serialize()
    assert m.deserialize(ref.serialize(), m.JointState) == ours


@given(st.lists(st.tuples(names, names, st.lists(floats, min_size=7, max_size=7)), max_size=4))
def test_tf_message_bytes_match_pycdr2(items) -> None:  # type: ignore[no-untyped-def]
    ours = m.TFMessage(
        [
            m.TransformStamped(
                m.Header(m.Time(1, 2), parent),
                child,
                m.Transform(m.Vector3(*v[:3]), m.Quaternion(*v[3:])),
            )
            for parent, child, v in items
        ]
    )
    ref = RefTFMessage(
        [
            RefTransformStamped(
                RefHeader(RefTime(1, 2), parent), child, RefVector3(*v[:3]), RefQuaternion(*v[3:])
            )
            for parent, child, v in items
        ]
    )
    assert m.serialize(ours) == ref.serialize()


def test_laser_scan_and_odometry_bytes_match_pycdr2() -> None:
    scan = m.LaserScan(
        m.Header(m.Time(3, 4), "laser"),
        -1.5,
        1.5,
        0.25,
        0.0,
        0.1,
        0.05,
        10.0,
        [1.0, 2.5, math.inf],
        [],
    )
    ref = RefLaserScan(
        RefHeader(RefTime(3, 4), "laser"),
        -1.5,
        1.5,
        0.25,
        0.0,
        0.1,
        0.05,
        10.0,
        [1.0, 2.5, math.inf],
        [],
    )
    assert m.serialize(scan) == ref.serialize()
    cov = [float(i) for i in range(36)]
    odom = m.Odometry(
        m.Header(m.Time(7, 8), "odom"),
        "base_link",
        m.PoseWithCovariance(m.Pose(m.Point(1, 2, 3), m.Quaternion(0, 0, 0, 1)), cov),
        m.TwistWithCovariance(m.Twist(m.Vector3(0.2, 0, 0), m.Vector3(0, 0, 0.5)), cov),
    )
    ref_odom = RefOdometry(
        RefHeader(RefTime(7, 8), "odom"),
        "base_link",
        RefPoseCov(RefVector3(1, 2, 3), RefQuaternion(0, 0, 0, 1), cov),
        RefTwistCov(RefVector3(0.2, 0, 0), RefVector3(0, 0, 0.5), cov),
    )
    assert m.serialize(odom) == ref_odom.serialize()
    assert m.deserialize(ref_odom.serialize(), m.Odometry) == odom


def test_joint_trajectory_controller_state_bytes_match_pycdr2() -> None:
    point = m.JointTrajectoryPoint([0.5, -1.0], [0.1], [], [2.0], m.Duration(1, 5))
    empty = m.MultiDOFJointTrajectoryPoint()
    base = m.MultiDOFJointTrajectoryPoint(
        [m.Transform(m.Vector3(1, 2, 3), m.Quaternion(0, 0, 0, 1))],
        [m.Twist(m.Vector3(0.5, 0, 0), m.Vector3(0, 0, 1))],
        [],
        m.Duration(0, 7),
    )
    ours = m.JointTrajectoryControllerState(
        m.Header(m.Time(9, 10), "arm"), ["j1", "j2"], point, point, m.JointTrajectoryPoint(),
        point, ["base"], base, empty, empty, base, 0.75,
    )  # fmt: skip
    ref_point = RefPoint([0.5, -1.0], [0.1], [], [2.0], RefDuration(1, 5))
    none = RefPoint([], [], [], [], RefDuration(0, 0))
    ref_empty = RefMultiPoint([], [], [], RefDuration(0, 0))
    ref_base = RefMultiPoint(
        [RefTransform(RefVector3(1, 2, 3), RefQuaternion(0, 0, 0, 1))],
        [RefTwist(RefVector3(0.5, 0, 0), RefVector3(0, 0, 1))],
        [],
        RefDuration(0, 7),
    )
    ref = RefJTCState(
        RefHeader(RefTime(9, 10), "arm"), ["j1", "j2"], ref_point, ref_point, none, ref_point,
        ["base"], ref_base, ref_empty, ref_empty, ref_base, 0.75,
    )  # fmt: skip
    assert m.serialize(ours) == ref.serialize()
    assert m.deserialize(ref.serialize(), m.JointTrajectoryControllerState) == ours


@dataclasses.dataclass(slots=True)
class Mixed(m.Message):
    """Every alignment case the generated codecs plan statically: sizes 1/2/4/8 after one
    another, fixed arrays, strings and sequences that make the offset unknown again, nested
    messages inline and inside sequences."""

    flag: bool = False
    wide: float = 0.0
    small: int = 0
    tag: str = ""
    bytes3: list = dataclasses.field(default_factory=lambda: [0, 0, 0])
    pair: list = dataclasses.field(default_factory=lambda: [0.0, 0.0])
    stamp: m.Time = dataclasses.field(default_factory=m.Time)
    level: int = 0
    values: list = dataclasses.field(default_factory=list)
    headers: list = dataclasses.field(default_factory=list)
    last: float = 0.0
    __typename__ = "robomodel_test/msg/Mixed"
    __fields__ = (
        ("flag", "bool"),
        ("wide", "float64"),
        ("small", "int16"),
        ("tag", "string"),
        ("bytes3", m.Array("uint8", 3)),
        ("pair", m.Array("float64", 2)),
        ("stamp", m.Time),
        ("level", "int8"),
        ("values", m.Seq("float32")),
        ("headers", m.Seq(m.Header)),
        ("last", "float64"),
    )


@dataclasses.dataclass
class RefMixed(pycdr2.IdlStruct, typename="robomodel_test/msg/Mixed"):
    flag: bool
    wide: float64
    small: int16
    tag: str
    bytes3: array[uint8, 3]
    pair: array[float64, 2]
    stamp: RefTime
    level: int8
    values: sequence[float32]
    headers: sequence[RefHeader]
    last: float64


_f32 = st.floats(width=32, allow_nan=False)
_f64 = st.floats(allow_nan=False)


@given(
    st.booleans(),
    _f64,
    st.integers(-(2**15), 2**15 - 1),
    st.text(max_size=7),
    st.lists(st.integers(0, 255), min_size=3, max_size=3),
    st.lists(_f64, min_size=2, max_size=2),
    st.integers(-(2**31), 2**31 - 1),
    st.integers(-128, 127),
    st.lists(_f32, max_size=3),
    st.lists(st.tuples(st.integers(0, 9), st.text(max_size=5)), max_size=3),
    _f64,
)
def test_mixed_alignment_bytes_match_pycdr2(  # type: ignore[no-untyped-def]
    flag, wide, small, tag, bytes3, pair, sec, level, values, headers, last
) -> None:
    ours = Mixed(
        flag, wide, small, tag, bytes3, pair, m.Time(sec, 7), level, values,
        [m.Header(m.Time(s, 1), f) for s, f in headers], last,
    )  # fmt: skip
    ref = RefMixed(
        flag, wide, small, tag, bytes3, pair, RefTime(sec, 7), level, values,
        [RefHeader(RefTime(s, 1), f) for s, f in headers], last,
    )  # fmt: skip
    payload = m.serialize(ours)
    assert payload == ref.serialize()
    # uint8[3] is encoded from a list and decoded as bytes (as rospy holds uint8 arrays)
    decoded = m.deserialize(payload, Mixed)
    assert decoded.bytes3 == bytes(bytes3)
    assert decoded == dataclasses.replace(ours, bytes3=bytes(bytes3))
    with pytest.raises(m.CDRError):
        m.deserialize(payload[:-1], Mixed)


def test_known_byte_vector() -> None:
    # std_msgs/Float64 1.5 as a ROS 2 node sends it: header, 4 bytes padding to 8, the double.
    assert m.serialize(m.Float64(1.5)) == bytes.fromhex("00010000" + "000000000000f83f")
    assert m.serialize(m.String("hi")) == bytes.fromhex("00010000" + "03000000" + "686900")


@pytest.mark.parametrize(
    "payload",
    [
        b"",
        b"\x00\x01",
        b"\x00\x01\x00\x00\x05",
        b"\x01\x00\x00\x00" + b"\x00" * 8,
        b"\x00\x01\x00\x00\xff\xff\xff\xff",
    ],
)
def test_malformed_payloads_raise_cdr_error(payload: bytes) -> None:
    with pytest.raises(m.CDRError):
        m.deserialize(payload, m.JointState)


def test_yaml_round_trip_and_errors() -> None:
    twist = m.message_from_yaml(m.Twist, "{linear: {x: 0.2}, angular: {z: 0.5}}")
    assert twist.linear.x == 0.2 and twist.angular.z == 0.5 and twist.linear.y == 0.0
    assert m.message_from_yaml(m.Float64, "data: 1").data == 1.0
    assert m.message_from_yaml(m.Float64MultiArray, "data: [1.0, 2]").data == [1.0, 2.0]
    assert m.message_from_yaml(m.Float64, "") == m.Float64()
    with pytest.raises(m.MessageTypeError) as info:
        m.message_from_yaml(m.Float64, "dat: 1.5")
    # no empty field-path prefix (": std_msgs/...") for a field of the message itself
    assert str(info.value) == (
        "std_msgs/msg/Float64 has no field 'dat' (did you mean 'data'?); its fields are: "
        "data (float64)"
    )
    with pytest.raises(m.MessageTypeError, match=r"^linear: geometry_msgs/msg/Vector3 has no"):
        m.message_from_yaml(m.Twist, "{linear: {xx: 1}}")
    with pytest.raises(m.MessageTypeError, match="expected a number"):
        m.message_from_yaml(m.Float64, "data: abc")
    with pytest.raises(m.MessageTypeError, match="out of range for int32"):
        m.message_from_yaml(m.Int32, "data: 4294967296")
    with pytest.raises(m.MessageTypeError, match="invalid YAML"):
        m.message_from_yaml(m.Float64, "data: [1,")


def test_echo_yaml_matches_ros2_topic_echo() -> None:
    text = m.message_to_yaml(m.JointState(m.Header(m.Time(1, 2), ""), ["j1"], [0.5]))
    assert text == (
        "header:\n  stamp:\n    sec: 1\n    nanosec: 2\n  frame_id: ''\nname:\n- j1\n"
        "position:\n- 0.5\nvelocity: []\neffort: []\n"
    )


def test_registry_and_field_order() -> None:
    assert m.get_message_type("std_msgs/Float64") is m.Float64
    assert m.get_message_type("geometry_msgs/msg/Twist") is m.Twist
    with pytest.raises(m.MessageTypeError, match="did you mean"):
        m.get_message_type("std_msgs/msg/Float46")
    for name in m.message_type_names():
        cls = m.get_message_type(name)
        assert [f.name for f in dataclasses.fields(cls)] == list(cls.field_names()), name


def test_publishers_and_subscriptions_generate_their_codecs_when_created() -> None:
    """The first message does not pay for code generation (it held up the ones behind it)."""
    from robomodel.runtime.msg import _cdr_decode, _cdr_encode, cdr

    _cdr_encode.encoders.pop(m.Imu, None)
    _cdr_decode.decoders.pop(m.Imu, None)
    cdr.prepare(m.Imu)
    encode, decode = _cdr_encode.encoders[m.Imu], _cdr_decode.decoders[m.Imu]
    msg = m.Imu(m.Header(m.Time(3, 4), "imu_link"))
    assert cdr.deserialize(cdr.serialize(msg), m.Imu) == msg
    assert _cdr_encode.encoders[m.Imu] is encode and _cdr_decode.decoders[m.Imu] is decode


def test_an_empty_message_is_one_byte_on_the_wire() -> None:
    """rosidl gives a message without fields ``uint8 structure_needs_at_least_one_member``: ROS 2
    sends std_msgs/Empty and std_srvs/Empty's halves as one byte after the header, nested too
    (the bytes below are pycdr2's of the same structure)."""
    from dataclasses import dataclass, field

    from pycdr2 import IdlStruct
    from pycdr2.types import float64, uint8

    from robomodel.runtime.msg import Empty, deserialize, serialize
    from robomodel.runtime.msg.schema import Message
    from robomodel.runtime.msg.types.std_srvs import Empty_Request, Empty_Response

    assert serialize(Empty()) == serialize(Empty_Request()) == b"\x00\x01\x00\x00\x00"
    assert deserialize(b"\x00\x01\x00\x00\x00", Empty_Response) == Empty_Response()
    assert deserialize(b"\x00\x01\x00\x00", Empty) == Empty()  # absent: accepted

    @dataclass(slots=True)
    class Holder(Message):
        empty: Empty = field(default_factory=Empty)
        value: float = 1.5
        __typename__ = "test_msgs/msg/Holder"
        __fields__ = (("empty", Empty), ("value", "float64"))

    @dataclass
    class E(IdlStruct, typename="E"):
        structure_needs_at_least_one_member: uint8 = 0

    @dataclass
    class H(IdlStruct, typename="H"):
        empty: E
        value: float64

    assert serialize(Holder()) == H(E(), 1.5).serialize()
    assert deserialize(H(E(), 2.5).serialize(), Holder) == Holder(Empty(), 2.5)


LAYOUT = """int32 a
geometry_msgs/Point[2] points
string s
float64[3] after_string
int16[] shorts
float64 d
uint8[] data
int64 big
string[2] names
string[] more
byte[] octets
bool[2] flags
std_msgs/Empty e
uint8[3] fixed_bytes
float64[] doubles
char c
uint16 tail
"""


def test_every_kind_of_field_against_rosbags() -> None:
    """A type of every kind of field, in an order that makes the generated code pad at run
    time and by format (a fixed array of messages after a value, fixed numbers after a string,
    numbers after sequences of every item size), encoded as rosbags encodes it and back."""
    from rosbags.typesys import Stores, get_types_from_msg, get_typestore

    from robomodel.runtime.msg import get_message_type
    from robomodel.runtime.msg._from_definition import build_message_class
    from robomodel.runtime.msg.definition import parse_message

    name = "test_msgs/msg/Layout"
    store = get_typestore(Stores.ROS2_JAZZY)
    store.register(get_types_from_msg(LAYOUT, name))
    cls = build_message_class(
        name, parse_message(LAYOUT, name, where="test")[name], get_message_type
    )
    point = get_message_type("geometry_msgs/msg/Point")
    values = {
        "a": -3, "s": "sé", "after_string": [1.5, -2.5, 3.5], "shorts": [-2, 3, 4],
        "d": 6.25, "data": b"\x01\xff", "big": -(2**40), "names": ["x", "yz"],
        "more": ["", "m"], "octets": b"\x07\x80", "flags": [True, False],
        "fixed_bytes": b"\x01\x02\x03", "doubles": [0.5], "c": 65, "tail": 65535,
    }  # fmt: skip
    ours = cls(**values, points=[point(1.0, 2.0, 3.0), point(-1.0, 0.0, 0.5)])  # type: ignore[call-arg]
    theirs_cls = store.types[name]
    points = [store.types["geometry_msgs/msg/Point"](x=p.x, y=p.y, z=p.z) for p in ours.points]  # type: ignore[attr-defined]
    theirs = theirs_cls(
        a=-3, points=points, s="sé", after_string=np.array([1.5, -2.5, 3.5]),
        shorts=np.array([-2, 3, 4], dtype=np.int16), d=6.25,
        data=np.array([1, 255], dtype=np.uint8), big=-(2**40), names=["x", "yz"],
        more=["", "m"], octets=np.array([7, -128], dtype=np.int8),
        flags=np.array([True, False]),
        e=store.types["std_msgs/msg/Empty"](structure_needs_at_least_one_member=0),
        fixed_bytes=np.array([1, 2, 3], dtype=np.uint8), doubles=np.array([0.5]), c=65,
        tail=65535,
    )  # fmt: skip
    expected = bytes(store.serialize_cdr(theirs, name))
    assert m.serialize(ours) == expected
    assert m.deserialize(expected, cls) == ours
    empty = cls()
    assert m.deserialize(m.serialize(empty), cls) == empty
    assert m.serialize(empty) == bytes(store.serialize_cdr(store.deserialize_cdr(
        m.serialize(empty), name), name))  # fmt: skip


def test_bad_text_is_one_line() -> None:
    """An invalid UTF-8 string, in a string field or a string sequence, is one CDRError."""
    bad_field = b"\x00\x01\x00\x00" + (3).to_bytes(4, "little") + b"\xff\xfe\x00"
    with pytest.raises(m.CDRError) as refused:
        m.deserialize(bad_field, m.String)
    assert str(refused.value) == "string is not valid UTF-8"
    names = m.serialize(m.JointState(name=["ok"]))
    at = names.index(b"ok")
    with pytest.raises(m.CDRError) as refused_in_list:
        m.deserialize(names[:at] + b"\xff\xfe" + names[at + 2 :], m.JointState)
    assert str(refused_in_list.value) == "string is not valid UTF-8"


def test_a_flavoured_class_is_built_through_its_own_maker() -> None:
    """A client library's class (rclpy's, rospy's) may build its instances itself
    (``__from_fields__``): the decoder calls it with the field values in wire order."""
    from typing import Any

    from robomodel.runtime.msg._from_definition import make_message_class

    made: list[tuple[Any, ...]] = []

    class Flavour:
        def class_name(self, name: str) -> str:
            return name.rsplit("/", 1)[-1]

        def class_body(self, name: str, specs: Any, constants: Any) -> Any:
            def from_fields(cls: Any, *values: Any) -> Any:
                made.append(values)
                obj = cls.__new__(cls)
                obj.x, obj.label = values
                return obj

            return (), {"__slots__": ("x", "label"), "__from_fields__": classmethod(from_fields)}

        def finish(self, cls: type) -> None:
            pass

    cls = make_message_class(
        "test_msgs/msg/Flavoured", (("x", "float64"), ("label", "string")), flavour=Flavour()
    )
    payload = b"\x00\x01\x00\x00" + struct.pack("<d", 2.5) + (2).to_bytes(4, "little") + b"a\x00"
    msg = m.deserialize(payload, cls)
    assert made == [(2.5, "a")] and (msg.x, msg.label) == (2.5, "a")  # type: ignore[attr-defined]
