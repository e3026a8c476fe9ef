"""rosrun's and ros2 run's node arguments (robomodel.launch.node_args), as rosgraph's
load_mappings / rospy and rcl's arguments.c read them."""

from __future__ import annotations

from pathlib import Path

import pytest

from robomodel.launch.node_args import NodeArgsError, parse_ros1_args, parse_ros2_args


def test_ros1_specials_private_params_and_remaps() -> None:
    parsed = parse_ros1_args(
        ["list", "__name:=cm", "__ns:=/rrbot", "_rate:=7", "_gains:=[1, 2.5]", "_on:=true",
         "_label:=text", "joint_states:=/r1/joint_states", "__log:=/tmp/x.log", "extra"]
    )  # fmt: skip
    assert parsed.args == ("list", "extra")
    assert (parsed.name, parsed.namespace) == ("cm", "/rrbot")
    assert parsed.params == {"rate": 7, "gains": [1, 2.5], "on": True, "label": "text"}
    assert parsed.remaps == (("joint_states", "/r1/joint_states"),)


def test_ros1_refuses_an_unknown_special_with_a_hint() -> None:
    with pytest.raises(NodeArgsError, match="did you mean __name"):
        parse_ros1_args(["__nam:=x"])


def test_ros2_ros_args_sections() -> None:
    parsed = parse_ros2_args(
        ["--x", "1", "--ros-args", "-r", "__node:=stp", "-r", "__ns:=/sensors",
         "-r", "tf_static:=/other", "-r", "someone_else:a:=b", "-r", "stp:c:=d",
         "-p", "rate:=20.0", "-p", "stp:frame:=world", "--params-file", "p.yaml",
         "--log-level", "debug", "--disable-rosout-logs", "--", "--y", "2"],
        default_name="static_transform_publisher",
    )  # fmt: skip
    assert parsed.args == ("--x", "1", "--y", "2")
    assert (parsed.name, parsed.namespace) == ("stp", "/sensors")
    assert parsed.remaps == (("tf_static", "/other"), ("c", "d"))  # node-scoped: only stp's
    assert parsed.params == {"rate": 20.0, "frame": "world"}
    assert parsed.params_files == (Path("p.yaml"),)


@pytest.mark.parametrize(
    ("argv", "said"),
    [
        (["--ros-args", "-x"], "unknown ROS argument '-x'"),
        (["--ros-args", "--remp", "a:=b"], "did you mean --remap"),
        (["--ros-args", "-p"], "-p needs a value"),
        (["--ros-args", "-r", "nothing"], "expected [node:]name:=value"),
    ],
)
def test_ros2_refuses_what_rcl_refuses(argv: list[str], said: str) -> None:
    with pytest.raises(NodeArgsError) as error:
        parse_ros2_args(argv, default_name="n")
    assert said in str(error.value)


_ALIAS_BOMB = "a: &a [x,x,x,x,x,x,x,x,x]\n" + "".join(
    f"{n}: &{n} [{', '.join([f'*{p}'] * 9)}]\n" for p, n in zip("abcdef", "bcdefg", strict=True)
)


@pytest.mark.parametrize(
    ("value", "said"),
    [
        ("[" * 5000 + "]" * 5000, "nested more than 100 levels deep"),
        (_ALIAS_BOMB, "aliases are expanded"),
    ],
)
def test_a_parameter_value_past_the_yaml_bounds_is_one_line(value: str, said: str) -> None:
    for parse in (
        lambda: parse_ros1_args([f"_p:={value}"]),
        lambda: parse_ros2_args(["--ros-args", "-p", f"p:={value}"], default_name="n"),
    ):
        with pytest.raises(NodeArgsError) as error:
            parse()
        message = str(error.value)
        assert "the value of '" in message and said in message
        assert "\n" not in message and len(message) < 200
