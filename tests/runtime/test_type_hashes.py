"""Every ROS 2 type robomodel defines has ROS 2 Jazzy's fields and RIHS01 type hash.

rmw_zenoh puts the type hash in every key expression and liveliness token, so a type whose
fields or hash differ from the ROS 2 install's is invisible to real nodes. Two references:
hashes published by ROS 2 itself (rmw_zenoh's design.md, the ROS 2 docs, /opt/ros/jazzy's
type-description JSON), and rosbags' Jazzy type store, which knows the fields of every message
of a ROS 2 Jazzy base install and computes RIHS01 independently of our code.
"""

from __future__ import annotations

import importlib
import pkgutil
from typing import Any

import pytest

import robomodel.runtime.msg as msg_package
from robomodel.runtime.msg.schema import (
    Array,
    Message,
    Seq,
    Spec,
    get_message_type,
    get_service_type,
    message_type_names,
    service_type_names,
)
from robomodel.runtime.msg.typehash import dds_type_name, type_hash
from tests.runtime.char_fields import has_char

typesys = pytest.importorskip("rosbags.typesys")
Nodetype = pytest.importorskip("rosbags.typesys.base").Nodetype

STORE = typesys.get_typestore(typesys.Stores.ROS2_JAZZY)

for _module in pkgutil.walk_packages(msg_package.__path__, "robomodel.runtime.msg."):
    if not _module.name.rsplit(".", 1)[-1].startswith("_"):
        importlib.import_module(_module.name)

# (type, RIHS01) as ROS 2 publishes them
CITED = [
    # rmw_zenoh docs/design.md, its key expression examples
    ("std_msgs/msg/String", "RIHS01_df668c740482bbd48fb39d76a70dfd4bd59db1288021743503259e948f6b1a18"),
    ("example_interfaces/srv/AddTwoInts", "RIHS01_e118de6bf5eeb66a2491b5bda11202e7b68f198d6f67922cf30364858239c81a"),
    # docs.ros.org, ``ros2 service info --verbose`` of turtlesim's std_srvs/srv/Empty
    ("std_srvs/srv/Empty", "RIHS01_5888399dedec5ccc85ea6451949fd2c9f97bfdf963f9a588821639fcd31b5d19"),
    # /opt/ros/jazzy/share/<pkg>/srv/<Srv>.json (rosidl_generator_type_description)
    ("std_srvs/srv/Trigger", "RIHS01_eeff2cd6fa5ad9d27cdf4dec64818317839b62f212a91e6b5304b634b2062c5f"),
    ("std_srvs/srv/SetBool", "RIHS01_abe9e4bb6b41b40e6789712c00ec8871923e089af3f667a79992a428cff2da0a"),
    ("rcl_interfaces/srv/ListParameters", "RIHS01_3e6062bfbb27bfb8730d4cef2558221f51a11646d78e7bb30a1e83afac3aad9d"),
    ("rcl_interfaces/srv/GetParameters", "RIHS01_bf9803d5c74cf989a5de3e0c2e99444599a627c7ff75f97b8c05b01003675cbc"),
    ("rcl_interfaces/srv/GetParameterTypes", "RIHS01_da199c878688b3e530bdfe3ca8f74cb9fa0c303101e980a9e8f260e25e1c80ca"),
    ("rcl_interfaces/srv/SetParameters", "RIHS01_56eed9a67e169f9cb6c1f987bc88f868c14a8fc9f743a263bc734c154015d7e0"),
    ("rcl_interfaces/srv/SetParametersAtomically", "RIHS01_0e192ef259c07fc3c07a13191d27002222e65e00ccec653ca05e856f79285fcd"),
    ("rcl_interfaces/srv/DescribeParameters", "RIHS01_845b484d71eb0673dae682f2e3ba3c4851a65a3dcfb97bddd82c5b57e91e4cff"),
    ("std_srvs/srv/SetBool_Request", "RIHS01_c62fbb99d94e1b25e8ef9e109f9581956bb1b3361a45a4e5810c36a90d29932e"),
    ("std_srvs/srv/SetBool_Response", "RIHS01_d0814e7f7b4880ab77e9c57426c7aa1562ab69f11eef8e2e968812f9cbd0b059"),
    ("service_msgs/msg/ServiceEventInfo", "RIHS01_41bcbbe07a75c9b52bc96bfd5c24d7f0fc0a08c0cb7921b3373c5732345a6f45"),
]  # fmt: skip


def _rosbags_base(name: str, bound: int) -> str:
    return f"string<={bound}" if bound else name


def _theirs(desc: Any) -> str:
    """A rosbags field description as ``.msg`` text (``float64[3]``, ``pkg/msg/T[]``...)."""
    kind, rest = desc
    if kind == Nodetype.BASE:
        return _rosbags_base(*rest)
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


def _all_message_types() -> list[type[Message]]:
    kinds = {name: get_message_type(name) for name in message_type_names()}
    for name in service_type_names():
        service = get_service_type(name)
        kinds[service.Request.__typename__] = service.Request
        kinds[service.Response.__typename__] = service.Response
    return [kinds[name] for name in sorted(kinds)]


EMPTY_MEMBER = ("structure_needs_at_least_one_member", "uint8")  # rosidl's, for ``Empty``
IN_JAZZY = [k for k in _all_message_types() if k.__typename__ in STORE.fielddefs]


def _by_name(name: str) -> Any:
    if "/srv/" not in name:
        return get_message_type(name)
    service, _, part = name.rpartition("_")
    if part in ("Request", "Response"):
        return getattr(get_service_type(service), part)
    return get_service_type(name)


def test_the_cited_hashes() -> None:
    for name, expected in CITED:
        if name.startswith("example_interfaces/"):
            continue  # not a package robomodel ships: built from its .srv below
        assert type_hash(_by_name(name)) == expected, name


def test_add_two_ints_hash_from_its_definition() -> None:
    """rmw_zenoh's own example, example_interfaces/srv/AddTwoInts, built from its .srv (the
    classes are named after creation so that they stay out of robomodel's registry)."""
    from dataclasses import dataclass

    from robomodel.runtime.msg.schema import Service

    @dataclass(slots=True)
    class Request(Message):
        __fields__ = (("a", "int64"), ("b", "int64"))
        a: int = 0
        b: int = 0

    @dataclass(slots=True)
    class Response(Message):
        __fields__ = (("sum", "int64"),)
        sum: int = 0

    class AddTwoInts(Service):
        pass

    Request.__typename__ = "example_interfaces/srv/AddTwoInts_Request"
    Response.__typename__ = "example_interfaces/srv/AddTwoInts_Response"
    AddTwoInts.Request, AddTwoInts.Response = Request, Response
    AddTwoInts.__typename__ = "example_interfaces/srv/AddTwoInts"
    assert type_hash(AddTwoInts) == dict(CITED)["example_interfaces/srv/AddTwoInts"]
    assert "example_interfaces/srv/AddTwoInts_Request" not in message_type_names()


def test_most_types_are_in_the_jazzy_store() -> None:
    """The comparison below is not vacuous. rosbags' store has the messages of a ROS 2 Jazzy
    base install (not its services', nor gazebo_msgs or control_msgs, which are checked through
    the cited service hashes and the SDK tests in tests/ros2wire)."""
    names = {k.__typename__ for k in IN_JAZZY}
    for name in (
        "sensor_msgs/msg/JointState",
        "tf2_msgs/msg/TFMessage",
        "rcl_interfaces/msg/ParameterEvent",
        "action_msgs/msg/GoalStatusArray",
        "lifecycle_msgs/msg/State",
        "trajectory_msgs/msg/JointTrajectory",
    ):
        assert name in names
    assert len(IN_JAZZY) > 40


@pytest.mark.parametrize("kind", IN_JAZZY, ids=lambda k: k.__typename__)
def test_fields_and_hash_match_ros2_jazzy(kind: type[Message]) -> None:
    _, fields = STORE.fielddefs[kind.__typename__]
    ours = [(n, _ours(s)) for n, s in kind.__fields__] or [EMPTY_MEMBER]
    assert ours == [(n, _theirs(d)) for n, d in fields]
    if not has_char(kind):
        assert type_hash(kind) == STORE.hash_rihs01(kind.__typename__)


def test_char_is_uint8_as_rosidl_has_it() -> None:
    """rosidl maps ``char`` to uint8 in the type description (rosbags, as ROS 1 does, to a
    char of its own), so the two disagree on types with a char field; ServiceEventInfo's hash,
    cited above, and every service hash built on it say rosidl's mapping is the one on the wire."""
    kind = get_message_type("service_msgs/msg/ServiceEventInfo")
    assert has_char(kind)
    assert type_hash(kind) == dict(CITED)["service_msgs/msg/ServiceEventInfo"]
    assert type_hash(kind) != STORE.hash_rihs01("service_msgs/msg/ServiceEventInfo")
    assert dds_type_name(kind.__typename__) == "service_msgs::msg::dds_::ServiceEventInfo_"


def test_action_types_derived_as_rosidl_does() -> None:
    """tf2_msgs/action/LookupTransform's SendGoal, GetResult and FeedbackMessage hashes as a
    Jazzy install has them (captured from /opt/ros/jazzy type descriptions, published with
    nano-ros' notes): make_action derives the services and the feedback message as rosidl."""
    from dataclasses import dataclass, field

    from robomodel.runtime.msg.action import make_action
    from robomodel.runtime.msg.types.builtin_interfaces import Duration, Time
    from robomodel.runtime.msg.types.geometry_msgs import TransformStamped

    @dataclass(slots=True)
    class Goal(Message):
        __fields__ = (
            ("target_frame", "string"),
            ("source_frame", "string"),
            ("source_time", Time),
            ("timeout", Duration),
            ("target_time", Time),
            ("fixed_frame", "string"),
            ("advanced", "bool"),
        )

    @dataclass(slots=True)
    class TF2Error(Message):
        __fields__ = (("error", "uint8"), ("error_string", "string"))

    @dataclass(slots=True)
    class Result(Message):
        __fields__ = (("transform", TransformStamped), ("error", TF2Error))
        transform: TransformStamped = field(default_factory=TransformStamped)

    @dataclass(slots=True)
    class Feedback(Message):
        pass

    Goal.__typename__ = "tf2_msgs/action/LookupTransform_Goal"
    TF2Error.__typename__ = "tf2_msgs/msg/TF2Error"
    Result.__typename__ = "tf2_msgs/action/LookupTransform_Result"
    Feedback.__typename__ = "tf2_msgs/action/LookupTransform_Feedback"
    # not registered: tf2_msgs' action stays out of the registry for the other tests
    action = make_action("tf2_msgs/action/LookupTransform", Goal, Result, Feedback, register=False)
    assert type_hash(action.SendGoal) == (
        "RIHS01_4646ff5706c86b04d0a1098d329951a9731a7517e16702905de6073cc72c8530"
    )
    assert type_hash(action.GetResult) == (
        "RIHS01_3cd1715751899e3167b5aec3e4ac194f7da9e8493a77285f9f6a4c914f5e8b24"
    )
    assert type_hash(action.FeedbackMessage) == (
        "RIHS01_10cb89922dcb103e95c185d43e8a5efa3d38db996f733151a2f3e2ac133f4839"
    )


def test_dds_type_names_both_ways() -> None:
    from robomodel.runtime.msg.typehash import ros_type_name

    assert dds_type_name("std_msgs/msg/String") == "std_msgs::msg::dds_::String_"
    assert ros_type_name("std_msgs::msg::dds_::String_") == "std_msgs/msg/String"
    assert ros_type_name("pkg::msg::dds_::A_") == "pkg/msg/A"  # a one-letter name
    assert ros_type_name("example_interfaces::srv::dds_::AddTwoInts_Request_") == (
        "example_interfaces/srv/AddTwoInts_Request"
    )
    for not_dds in (
        "std_msgs::msg::String_",  # three parts
        "a::b::c::d::e_",  # five
        "std_msgs::msg::rti_::String_",  # not dds_
        "std_msgs::msg::dds_::String",  # no trailing underscore
        "std_msgs::msg::dds_::_",  # nothing before it
        "::msg::dds_::String_",  # no package
        "std_msgs::::dds_::String_",  # no kind
    ):
        assert ros_type_name(not_dds) is None, not_dds


def test_service_hashes_are_rosidl_s_and_kept() -> None:
    """RIHS01 of a service as rosidl computes it (the cited hash), its description's event
    part, and the same string object the second time (it is computed once per class)."""
    from robomodel.runtime.msg.schema import get_service_type
    from robomodel.runtime.msg.typehash import same_type, type_description

    srv = get_service_type("std_srvs/srv/SetBool")
    first = type_hash(srv)
    assert first == dict(CITED)["std_srvs/srv/SetBool"]
    assert type_hash(srv) is first
    description = type_description(srv)
    fields = description["type_description"]["fields"]
    assert [f["name"] for f in fields] == ["request_message", "response_message", "event_message"]
    assert fields[2]["type"]["nested_type_name"] == "std_srvs/srv/SetBool_Event"
    assert fields[2]["type"]["string_capacity"] == 0 and fields[2]["type"]["capacity"] == 0
    event = next(
        d
        for d in description["referenced_type_descriptions"]
        if d["type_name"] == "std_srvs/srv/SetBool_Event"
    )
    assert [f["type"]["capacity"] for f in event["fields"]] == [0, 1, 1]
    assert [f["type"]["type_id"] for f in event["fields"]] == [1, 97, 97]
    trigger = get_service_type("std_srvs/srv/Trigger")
    assert type_hash(trigger) != first
    assert same_type(srv, srv) and not same_type(srv, trigger)
