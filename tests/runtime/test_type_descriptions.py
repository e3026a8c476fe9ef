"""A node's ``~/get_type_description`` in one process, and descriptions read back into types.

The wire test against an independent peer is ``tests/ros2wire/test_type_descriptions.py``.
"""

from __future__ import annotations

import pytest

from robomodel.runtime.context import Context
from robomodel.runtime.msg._from_definition import build_message_class
from robomodel.runtime.msg.schema import Message, get_message_type
from robomodel.runtime.msg.typehash import type_hash
from robomodel.runtime.msg.types import type_description_interfaces as tdi
from robomodel.runtime.msg.types.rcl_interfaces import DescribeParameters_Response
from robomodel.runtime.transport.base import Endpoint
from robomodel.runtime.type_descriptions import describe, description_hash
from robomodel.runtime.type_learning import _ask, fielddefs_of

typesys = pytest.importorskip("rosbags.typesys")
STORE = typesys.get_typestore(typesys.Stores.ROS2_JAZZY)


def _call(
    ctx: Context, type_hash_text: str, sources: bool = True
) -> tdi.GetTypeDescription_Response:
    request = tdi.GetTypeDescription_Request("ignored/msg/Name", type_hash_text, sources)
    response: tdi.GetTypeDescription_Response = ctx.call_service(
        "/arm/talker/get_type_description", tdi.GetTypeDescription, request
    )
    return response


def test_a_node_describes_the_types_it_uses_by_hash_alone() -> None:
    with Context() as ctx:
        node = ctx.create_node("talker", "/arm")
        image = get_message_type("sensor_msgs/msg/Image")
        node.create_publisher(image, "camera")
        wanted = STORE.hash_rihs01("sensor_msgs/msg/Image")
        answer = _call(ctx, "RIHS01_" + wanted[7:].upper())  # hex digits of either case
        assert answer.successful and answer.failure_reason == ""
        assert answer.type_description.type_description.type_name == "sensor_msgs/msg/Image"
        assert description_hash(answer.type_description) == wanted
        names = [s.type_name for s in answer.type_sources]
        assert names == [
            "sensor_msgs/msg/Image",
            "builtin_interfaces/msg/Time",
            "std_msgs/msg/Header",
        ]
        assert not _call(ctx, wanted, sources=False).type_sources
        # /rosout's and the parameter services' types are the node's too, as in rcl
        assert _call(ctx, STORE.hash_rihs01("rcl_interfaces/msg/Log")).successful
        unused = _call(ctx, STORE.hash_rihs01("std_msgs/msg/Int8"))
        assert (unused.successful, unused.failure_reason) == (
            False,
            "Type not currently in use by this node",
        )
        bad_hashes = (
            "RIHS02_" + "0" * 64,
            "RIHS01_" + "0" * 63,
            "RIHS01_" + "g" * 64,
            "RIHS01_" + " 0" * 32,
            "",
        )
        for bad in bad_hashes:
            assert _call(ctx, bad).failure_reason == "Failed to parse type hash"


@pytest.mark.parametrize(
    "kind",
    [
        get_message_type("sensor_msgs/msg/Image"),  # uint8[], nested
        get_message_type("geometry_msgs/msg/PoseWithCovariance"),  # float64[36]
        DescribeParameters_Response,  # FloatingPointRange[<=1]
        tdi.IndividualTypeDescription,  # string<=255
    ],
)
def test_a_description_builds_a_type_of_the_same_hash(kind: type[Message]) -> None:
    described = fielddefs_of(describe(kind))
    built: dict[str, type[Message]] = {}

    def lookup(name: str) -> type[Message]:
        if name not in built:
            built[name] = build_message_class(name, described[name], lookup)
        return built[name]

    assert type_hash(lookup(kind.__typename__)) == type_hash(kind)


def test_a_description_that_does_not_hash_to_the_token_s_is_refused() -> None:
    with Context() as ctx:
        node = ctx.create_node("talker", "/arm")
        node.create_publisher(get_message_type("std_msgs/msg/String"), "chatter")
        string_hash = type_hash(get_message_type("std_msgs/msg/String"))
        told = Endpoint("/arm/talker", "/arm/chatter", "std_msgs/msg/String", type_hash=string_hash)
        assert _ask(ctx, told, 2.0) is not None
        # a node whose answer is for another hash than the token's (here: it has none)
        other = Endpoint("/arm/talker", "/arm/chatter", "std_msgs/msg/String",
                         type_hash="RIHS01_" + "1" * 64)  # fmt: skip
        assert _ask(ctx, other, 2.0) is None

    def lie(request: tdi.GetTypeDescription_Request) -> tdi.GetTypeDescription_Response:
        int8 = describe(get_message_type("std_msgs/msg/Int8"))
        int8.type_description.type_name = "std_msgs/msg/String"
        return tdi.GetTypeDescription_Response(True, "", int8)

    with Context() as ctx:
        ctx.transport.create_service(
            "/liar", "/liar/get_type_description", tdi.GetTypeDescription, lie
        )
        liar = Endpoint("/liar", "/chatter", "std_msgs/msg/String", type_hash=string_hash)
        assert _ask(ctx, liar, 2.0) is None


def test_a_type_leaves_the_cache_with_the_last_entity_using_it() -> None:
    wanted = STORE.hash_rihs01("sensor_msgs/msg/Image")
    image = get_message_type("sensor_msgs/msg/Image")
    with Context() as ctx:
        node = ctx.create_node("talker", "/arm")
        first = node.create_publisher(image, "camera")
        second = node.create_subscription(image, "other", lambda _: None)
        first.destroy()
        assert _call(ctx, wanted).successful  # the subscription still uses it
        second.destroy()
        assert _call(ctx, wanted).failure_reason == "Type not currently in use by this node"
