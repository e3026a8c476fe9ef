"""A definition that nests its own type (``SelfRec child``, or ``A -> B -> A``), from any source,
is refused in one line (MessageTypeError, which the recorder and ``topic echo`` turn into one
warning for that topic) instead of recursing until Python's RecursionError."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest

from robomodel.runtime.msg import _resolver, get_message_type
from robomodel.runtime.msg.definition import recursion_in
from robomodel.runtime.msg.schema import MessageTypeError

pytest.importorskip("rosbags.typesys")

SEPARATOR = "=" * 80


def test_a_self_recursive_peer_definition_is_refused_in_one_line() -> None:
    with pytest.raises(MessageTypeError) as info:
        _resolver.learn_definition("evil_msgs/SelfRec", "int32 a\nSelfRec child\n")
    message = str(info.value)
    assert "\n" not in message
    assert message.startswith("evil_msgs/msg/SelfRec: its definition contains itself")
    assert "(evil_msgs/msg/SelfRec -> evil_msgs/msg/SelfRec)" in message
    # not learned: the name stays unknown, and a legitimate type learned beside it works
    with pytest.raises(MessageTypeError, match="unknown message type 'evil_msgs/SelfRec'"):
        get_message_type("evil_msgs/SelfRec")
    _resolver.learn_definition("fine_msgs/Chatter", "string data\n")
    assert get_message_type("fine_msgs/Chatter")(data="x").data == "x"


def test_mutual_recursion_is_refused_whether_learned_at_once_or_in_two_steps() -> None:
    text = f"RecB b\n{SEPARATOR}\nMSG: evil_msgs/RecB\nRecA[] a\n"
    with pytest.raises(MessageTypeError, match=r"RecA -> evil_msgs/msg/RecB -> evil_msgs/msg/RecA"):
        _resolver.learn_definition("evil_msgs/RecA", text)
    # C uses D, which nobody defined yet; then a D that uses C closes the loop
    _resolver.learn_definition("evil_msgs/RecC", "RecD d\n")
    with pytest.raises(MessageTypeError, match=r"its definition contains itself"):
        _resolver.learn_definition("evil_msgs/RecD", "RecC c\n")


def test_a_type_description_that_nests_itself_is_refused() -> None:
    nested = (2, "evil_msgs/msg/Described")
    with pytest.raises(MessageTypeError, match=r"^evil_msgs/msg/Described: its definition"):
        _resolver.learn_fielddefs({"evil_msgs/msg/Described": ((), [("child", (4, (nested, 0)))])})


@pytest.fixture
def recursive_package(tmp_path: Path) -> Iterator[Path]:
    package = tmp_path / "ws" / "loop_msgs"
    (package / "msg").mkdir(parents=True)
    (package / "package.xml").write_text(
        '<package format="3"><name>loop_msgs</name><version>0.0.0</version></package>'
    )
    (package / "msg" / "Self.msg").write_text("float64 x\nSelf[] children\n")
    (package / "msg" / "Ping.msg").write_text("Pong pong\n")
    (package / "msg" / "Pong.msg").write_text("Ping ping\n")
    (package / "msg" / "Leaf.msg").write_text("std_msgs/Header header\n")
    _resolver.configure(package_paths=(tmp_path / "ws",))
    yield package
    _resolver.configure(package_paths=())


def test_recursive_package_files_are_refused_in_one_line(recursive_package: Path) -> None:
    with pytest.raises(MessageTypeError, match=r"^loop_msgs/msg/Self: .*\(loop_msgs/msg/Self -> "):
        get_message_type("loop_msgs/msg/Self")
    with pytest.raises(MessageTypeError) as info:
        get_message_type("loop_msgs/Ping")
    assert "loop_msgs/msg/Ping -> loop_msgs/msg/Pong -> loop_msgs/msg/Ping" in str(info.value)
    # the refusal leaves nothing half-built: the same answer again, and other types build
    with pytest.raises(MessageTypeError, match="contains itself"):
        get_message_type("loop_msgs/Pong")
    assert get_message_type("loop_msgs/Leaf").field_names() == ("header",)


def test_recursion_in_finds_long_chains_without_recursing() -> None:
    count = 5_000  # deeper than Python's recursion limit
    chain = {f"p/msg/T{i}": ((), [("next", (2, f"p/msg/T{i + 1}"))]) for i in range(count)}
    assert recursion_in(chain) is None
    chain[f"p/msg/T{count}"] = ((), [("back", (2, "p/msg/T0"))])
    found = recursion_in(chain)
    assert found is not None and found[0] == found[-1] == "p/msg/T0" and len(found) == count + 2
