"""rmw_zenoh's wire format, byte for byte, against values written in rmw_zenoh's sources.

Cited: ros2/rmw_zenoh ``docs/design.md`` (section "Topic and Service name mapping to Zenoh key
expressions" and "Graph Cache": the key and token examples of demo_nodes_cpp's talker,
listener and add_two_ints), ``rmw_zenoh_cpp/src/detail/liveliness_utils.cpp``
(``qos_to_keyexpr``, ``Entity::make``), ``qos.cpp`` (defaults) and ``attachment_helpers.cpp``
(0.2.4). The attachment bytes are also checked against zenoh-ext's own serializer (the one
rmw_zenoh calls), an independent implementation.
"""

from __future__ import annotations

import struct

import pytest

from robomodel.runtime.msg import String
from robomodel.runtime.msg.typehash import dds_type_name, ros_type_name, type_hash
from robomodel.runtime.qos import (
    Durability,
    History,
    QoSProfile,
    Reliability,
    latched,
    sensor_data,
)
from robomodel.runtime.transport._attachment import SequenceTracker
from robomodel.runtime.transport.rmw_zenoh import (
    ATTACHMENT_SIZE,
    EntityKind,
    EntityToken,
    encode_attachment,
    entity_gid,
    parse_attachment,
    qos_from_key,
    qos_to_key,
    topic_key,
)
from tests.conftest import unique_domain
from tests.timing import scaled

STRING_HASH = "RIHS01_df668c740482bbd48fb39d76a70dfd4bd59db1288021743503259e948f6b1a18"
ADD_TWO_INTS_HASH = "RIHS01_e118de6bf5eeb66a2491b5bda11202e7b68f198d6f67922cf30364858239c81a"


def test_topic_and_service_keys_are_design_md_s() -> None:
    assert type_hash(String) == STRING_HASH
    dds = dds_type_name("std_msgs/msg/String")
    assert topic_key(0, "/chatter", dds, STRING_HASH) == (
        "0/chatter/std_msgs::msg::dds_::String_/" + STRING_HASH
    )
    assert topic_key(0, "/robot1/chatter", dds, STRING_HASH) == (
        "0/robot1/chatter/std_msgs::msg::dds_::String_/" + STRING_HASH
    )
    service = dds_type_name("example_interfaces/srv/AddTwoInts")
    assert topic_key(2, "/add_two_ints", service, ADD_TWO_INTS_HASH) == (
        "2/add_two_ints/example_interfaces::srv::dds_::AddTwoInts_/" + ADD_TWO_INTS_HASH
    )
    assert ros_type_name("example_interfaces::srv::dds_::AddTwoInts_") == (
        "example_interfaces/srv/AddTwoInts"
    )
    assert ros_type_name("std_msgs::msg::String") is None


LISTENER_NODE = "@ros2_lv/2/aac3178e146ba6f1fc6e6a4085e77f21/0/0/NN/%/%/listener"
LISTENER_SUB = (
    "@ros2_lv/2/aac3178e146ba6f1fc6e6a4085e77f21/0/10/MS/%/%/listener/%chatter/"
    f"std_msgs::msg::dds_::String_/{STRING_HASH}/::,10:,:,:,,"
)
TALKER_PUB = (
    "@ros2_lv/2/8b20917502ee955ac4476e0266340d5c/0/10/MP/%/%/talker/%chatter/"
    f"std_msgs::msg::dds_::String_/{STRING_HASH}/::,7:,:,:,,"
)
SERVER = (
    "@ros2_lv/2/f9980ee0495eaafb3e38f0d19e2eae12/0/10/SS/%/%/add_two_ints_server/"
    f"%add_two_ints/example_interfaces::srv::dds_::AddTwoInts_/{ADD_TWO_INTS_HASH}/::,10:,:,:,,"
)


def test_tokens_are_built_as_design_md_shows() -> None:
    node = EntityToken(
        2, "aac3178e146ba6f1fc6e6a4085e77f21", 0, 0, EntityKind.NODE, "/", "listener"
    )
    assert node.key() == LISTENER_NODE
    sub = EntityToken(
        2,
        "aac3178e146ba6f1fc6e6a4085e77f21",
        0,
        10,
        EntityKind.SUBSCRIPTION,
        "/",
        "listener",
        name="/chatter",
        dds_type="std_msgs::msg::dds_::String_",
        type_hash=STRING_HASH,
        qos=qos_to_key(QoSProfile(depth=10)),
    )
    assert sub.key() == LISTENER_SUB


@pytest.mark.parametrize("key", [LISTENER_NODE, LISTENER_SUB, TALKER_PUB, SERVER])
def test_tokens_parse_back(key: str) -> None:
    token = EntityToken.parse(key)
    assert token is not None and token.key() == key
    assert token.domain_id == 2 and token.namespace == "/" and token.enclave == "/"


def test_a_parsed_token_says_what_the_graph_needs() -> None:
    pub = EntityToken.parse(TALKER_PUB)
    assert pub is not None
    assert (pub.kind, pub.node, pub.name, pub.node_id, pub.entity_id) == (
        EntityKind.PUBLISHER,
        "/talker",
        "/chatter",
        0,
        10,
    )
    assert qos_from_key(pub.qos) == QoSProfile(depth=7)
    ns = EntityToken(0, "ab", 3, 7, EntityKind.PUBLISHER, "/robot1/arm", "rsp", name="/robot1/tf",
                     dds_type="tf2_msgs::msg::dds_::TFMessage_", type_hash="RIHS01_x", qos="::,:,:,:,,")  # fmt: skip
    key = ns.key()
    assert "/%robot1%arm/rsp/%robot1%tf/" in key
    parsed = EntityToken.parse(key)
    assert parsed is not None and parsed.node == "/robot1/arm/rsp" and parsed.name == "/robot1/tf"


@pytest.mark.parametrize(
    "key",
    [
        "@ros2_lv/2/aac3/0/0/NN/%/%",  # too few parts
        "@ros2_lv/2/aac3/0/0/XX/%/%/listener",  # unknown entity kind
        "@ros2/2/aac3/0/0/NN/%/%/listener",  # wrong admin space
        "@ros2_lv/two/aac3/0/0/NN/%/%/listener",  # domain not a number
        "@ros2_lv/2//0/0/NN/%/%/listener",  # an empty part
        LISTENER_SUB.replace("::,10:,:,:,,", "::,10:,"),  # QoS of too few fields
        LISTENER_SUB.replace("::,10:", "9::,10:"),  # unknown reliability
        LISTENER_SUB.replace("::,10:", "::,1x0:"),  # depth not a number
    ],
)
def test_malformed_tokens_are_refused(key: str) -> None:
    assert EntityToken.parse(key) is None


@pytest.mark.parametrize(
    ("key", "node_id", "entity_id"),
    [
        ("@ros2_lv/2/aac3/0/0/NN/%/%/listener/extra", 0, 0),  # only parts 0-8 are read
        ("@ros2_lv/2/aac3/0/-1/NN/%/%/listener", 0, "-1"),  # ids are strings there
        ("@ros2_lv/2/aac3/0/²/NN/%/%/listener", 0, "²"),
        ("@ros2_lv/ 2x/aac3/0/0/NN/%/%/listener", 0, 0),  # std::stoul(" 2x") is 2
    ],
)
def test_tokens_entity_make_accepts_are_read(
    key: str, node_id: int | str, entity_id: int | str
) -> None:
    """``Entity::make`` (liveliness_utils.cpp, Jazzy 0.2.10) checks the number of parts (at
    least, not exactly), the admin space and kind, reads the domain with ``std::stoul`` and
    keeps ids as strings."""
    token = EntityToken.parse(key)
    assert token is not None and token.node == "/listener" and token.domain_id == 2
    assert (token.node_id, token.entity_id) == (node_id, entity_id)


def test_qos_strings_elide_rmw_zenoh_s_defaults() -> None:
    assert qos_to_key(QoSProfile(depth=10)) == "::,10:,:,:,,"  # rclcpp's default
    assert qos_to_key(QoSProfile(depth=42)) == "::,:,:,:,,"  # rmw_zenoh's default depth
    assert qos_to_key(latched()) == ":1:,1:,:,:,,"  # /tf_static, /robot_description
    assert qos_to_key(sensor_data()) == "2::,5:,:,:,,"
    assert qos_to_key(QoSProfile(depth=3, history=History.KEEP_ALL)) == "::2,3:,:,:,,"
    assert qos_from_key(":1:,1:,:,:,,") == QoSProfile(1, Durability.TRANSIENT_LOCAL)
    assert qos_from_key("2::,5:,:,:,,") == QoSProfile(
        5, Durability.VOLATILE, Reliability.BEST_EFFORT
    )
    # Jazzy before 0.2.3 wrote volatile as 2 (its default durability was transient local)
    assert qos_from_key(":2:,10:,:,:,,") == QoSProfile(10)
    assert qos_from_key("::,0:,:,:,,") == QoSProfile(42)  # depth 0: rmw_zenoh picks 42


def test_attachment_bytes_are_zenoh_ext_serialization() -> None:
    zenoh_ext = pytest.importorskip("zenoh.ext")
    gid = bytes(range(16))
    ours = encode_attachment(7, 1_700_000_000_123_456_789, gid)
    theirs = zenoh_ext.z_serialize(
        (zenoh_ext.Int64(7), zenoh_ext.Int64(1_700_000_000_123_456_789), gid)
    ).to_bytes()
    assert ours == theirs and len(ours) == ATTACHMENT_SIZE == 33
    parsed = parse_attachment(ours)
    assert parsed is not None
    assert (parsed.sequence_number, parsed.source_timestamp_ns, parsed.gid) == (
        7,
        1_700_000_000_123_456_789,
        gid,
    )


def test_the_labelled_attachment_of_older_releases_is_read() -> None:
    zenoh_ext = pytest.importorskip("zenoh.ext")
    gid = bytes(range(100, 116))
    legacy = zenoh_ext.z_serialize(
        (
            "sequence_number",
            zenoh_ext.Int64(3),
            "source_timestamp",
            zenoh_ext.Int64(99),
            "source_gid",
            gid,
        )
    ).to_bytes()
    parsed = parse_attachment(legacy)
    assert parsed is not None and (
        parsed.sequence_number,
        parsed.source_timestamp_ns,
        parsed.gid,
    ) == (3, 99, gid)


@pytest.mark.parametrize(
    "raw",
    [
        b"",
        b"\x00" * 32,  # one byte short
        struct.pack("<qqB", 1, 2, 15) + bytes(15) + b"\x00",  # a GID length that is not 16
        struct.pack("<qqB", 1, 2, 16) + bytes(16) + b"\x00",  # one byte too many
        b"std_msgs/msg/Float64|x|1",  # robomodel's own format before rmw_zenoh's
        b"\x0fsequence_number" + bytes(60),  # labelled, then garbage
    ],
)
def test_malformed_attachments_are_refused(raw: bytes) -> None:
    assert parse_attachment(raw) is None


def test_gid_is_xxh3_128_of_the_token_low_half_first() -> None:
    xxhash = pytest.importorskip("xxhash")
    digest = xxhash.xxh3_128(TALKER_PUB.encode()).intdigest()
    gid = entity_gid(TALKER_PUB)
    assert gid[:8] == (digest & (2**64 - 1)).to_bytes(8, "little")
    assert gid[8:] == (digest >> 64).to_bytes(8, "little")
    assert entity_gid(LISTENER_SUB) != gid


def test_sequence_numbers_count_losses_as_rmw_zenoh() -> None:
    """``SubscriptionData::add_new_message``: ``|seq - last| - 1`` lost on a jump either way."""
    seen = SequenceTracker()
    gid = b"g" * 16
    for n in (1, 2, 5):
        seen.record(gid, n)
    assert seen.lost == 2  # 3 and 4, as rmw_zenoh's MESSAGE_LOST counts them
    seen.record(gid, 5)  # the same number again: no gap
    assert seen.lost == 2
    seen.record(b"h" * 16, 5)  # another publisher's own numbers
    assert seen.lost == 2
    seen.record(gid, 1)  # a restart of the same GID: 2, 3, 4 counted as a gap
    assert seen.lost == 5


def test_sequence_state_is_bounded_when_gids_flood() -> None:
    seen = SequenceTracker(max_publishers=64)
    for i in range(10_000):
        seen.record(i.to_bytes(16, "little"), 1)
    assert len(seen) == 64
    assert seen.lost == 0


def test_the_publisher_heard_least_recently_is_the_one_forgotten() -> None:
    """The tracker's memory is least recently used first out: a publisher heard again moves
    to the back, so a flood of new GIDs does not make it count its own next sample lost."""
    seen = SequenceTracker(max_publishers=3)
    steady = b"s" * 16
    seen.record(steady, 1)
    for i in range(2):
        seen.record(bytes([i]) * 16, 1)
    seen.record(steady, 2)  # heard again: now the most recent
    seen.record(b"n" * 16, 1)  # a fourth GID: the oldest other one goes, not steady
    seen.record(steady, 4)  # 3 lost, counted against the remembered 2
    assert seen.lost == 1
    seen.record(bytes([0]) * 16, 9)  # forgotten, so this is a first sample: nothing counted
    assert seen.lost == 1


def test_a_publisher_restarting_with_the_same_gid_loses_none_of_8_messages() -> None:
    """A publisher that restarts with the same GID numbers its samples from 1
    again; rmw_zenoh delivers them (robomodel dropped those up to 1023 below the last)."""
    from robomodel.runtime import Context
    from robomodel.runtime.msg import Float64, serialize
    from robomodel.runtime.transport.rmw_zenoh import encode_attachment

    got: list[float] = []
    with Context("zenoh", domain_id=int(unique_domain())) as ctx:
        sub = ctx.create_node("sub").create_subscription(
            Float64, "/chatter", lambda m: got.append(m.data)
        )
        session = ctx.transport.session  # type: ignore[attr-defined]
        key = ctx.transport.data_key("/chatter", Float64)  # type: ignore[attr-defined]
        gid = bytes(range(16))
        # 5 messages, then the publisher restarts with the same GID and sends 3 more
        for value, sequence in enumerate((1, 2, 3, 4, 5, 1, 2, 3)):
            attachment = encode_attachment(sequence, 0, gid)
            session.put(key, serialize(Float64(float(value))), attachment=attachment)
        ctx.spin(duration_s=scaled(10.0), until=lambda: len(got) >= 8)
    assert got == [float(v) for v in range(8)]
    assert sub.get_messages_lost() == 3  # |1 - 5| - 1, as rmw_zenoh
