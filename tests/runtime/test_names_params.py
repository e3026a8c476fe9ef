"""ROS 2 name rules and node parameters."""

from __future__ import annotations

from pathlib import Path

import pytest

from robomodel.runtime import Context, ManualClock, ParameterError
from robomodel.runtime.names import NameError_, expand_topic_name, parse_remapping
from robomodel.runtime.params import (
    dump_parameters_yaml,
    load_parameters_file,
    parse_parameter_value,
)


@pytest.mark.parametrize(
    ("topic", "node", "ns", "expected"),
    [
        ("chatter", "talker", "/", "/chatter"),
        ("chatter", "talker", "/robot1", "/robot1/chatter"),
        ("/chatter", "talker", "/robot1", "/chatter"),
        ("~/state", "talker", "/robot1", "/robot1/talker/state"),
        ("~", "talker", "/", "/talker"),
        ("a/b", "n", "ns", "/ns/a/b"),
    ],
)
def test_expansion(topic: str, node: str, ns: str, expected: str) -> None:
    assert expand_topic_name(topic, node, ns) == expected


@pytest.mark.parametrize("bad", ["", "1abc", "a//b", "a/", "a b", "a-b", "/a/2b"])
def test_invalid_names(bad: str) -> None:
    with pytest.raises(NameError_):
        expand_topic_name(bad, "n", "/")


def test_remapping_applies_to_expanded_names() -> None:
    ctx = Context(clock=ManualClock())
    node = ctx.create_node("jsp", "/arm", remappings=dict([parse_remapping("joint_states:=/js")]))
    assert node.resolve_topic_name("joint_states") == "/js"
    assert node.resolve_topic_name("/arm/joint_states") == "/js"
    assert node.resolve_topic_name("other") == "/arm/other"
    with pytest.raises(NameError_):
        parse_remapping("nope")


def test_parameters_declare_get_set_types_and_callbacks() -> None:
    ctx = Context(clock=ManualClock())
    node = ctx.create_node("n", parameters={"rate": 20, "gain": 2})
    assert node.declare_parameter("rate", 10) == 20  # override wins
    assert node.declare_parameter("gain", 1.5) == 2.0 and isinstance(
        node.get_parameter("gain"), float
    )
    assert node.declare_parameter("name", "x") == "x"
    result = node.set_parameters({"rate": "fast"})
    assert not result.successful and "is of type {integer}" in result.reason
    node.parameters.add_set_callback(
        lambda changes: __import__("robomodel.runtime.params", fromlist=["SetResult"]).SetResult(
            changes.get("rate", 1) > 0, "rate must be positive"
        )
    )
    assert node.set_parameters({"rate": -1}).reason == "rate must be positive"
    assert node.get_parameter("rate") == 20  # unchanged
    assert node.set_parameters({"rate": 5, "name": "y"}).successful
    assert node.get_parameter("name") == "y"
    assert not node.set_parameters({"undeclared": 1}).successful
    with pytest.raises(ParameterError, match="did you mean rate"):
        node.get_parameter("rat")


def test_parameter_files(tmp_path: Path) -> None:
    path = tmp_path / "params.yaml"
    path.write_text(
        "/**:\n  ros__parameters:\n    use_sim_time: true\n"
        "joint_state_publisher:\n  ros__parameters:\n    rate: 50\n    zeros:\n      joint1: 0.5\n"
    )
    values = load_parameters_file(path, "/joint_state_publisher")
    assert values == {"use_sim_time": True, "rate": 50, "zeros.joint1": 0.5}
    assert load_parameters_file(path, "/other") == {"use_sim_time": True}
    text = dump_parameters_yaml("/joint_state_publisher", {"rate": 50, "zeros.joint1": 0.5})
    assert (
        text
        == "/joint_state_publisher:\n  ros__parameters:\n    rate: 50\n    zeros:\n      joint1: 0.5\n"
    )
    bad = tmp_path / "bad.yaml"
    bad.write_text("node:\n  ros__parameters:\n    a: [1,\n")
    with pytest.raises(ParameterError, match=r"bad.yaml:\d+:\d+: error: invalid YAML"):
        load_parameters_file(bad, "/node")


def test_parse_parameter_value() -> None:
    assert parse_parameter_value("1.5") == 1.5
    assert parse_parameter_value("true") is True
    assert parse_parameter_value("[1, 2]") == [1, 2]
    assert parse_parameter_value("hello") == "hello"
