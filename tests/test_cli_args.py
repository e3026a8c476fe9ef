"""``name:=value`` may come after options, as roslaunch, ros2 launch and xacro accept it."""

from __future__ import annotations

from collections.abc import Callable

from tests.conftest import EXAMPLES, ToolResult

RRBOT = str(EXAMPLES / "rrbot_description" / "urdf" / "rrbot.xacro")


def test_launch_args_after_options(cli: Callable[..., ToolResult]) -> None:
    world = str(EXAMPLES / "rrbot_gazebo" / "launch" / "rrbot_world.launch")
    before = cli("launch", world, "paused:=true", "--package-path", str(EXAMPLES), "--dump-params")
    after = cli("launch", world, "--package-path", str(EXAMPLES), "--dump-params", "paused:=true")
    assert before.code == after.code == 0, after.err
    assert before.out == after.out


def test_xacro_mappings_after_options(cli: Callable[..., ToolResult]) -> None:
    first = cli("xacro", RRBOT, "--package-path", str(EXAMPLES))
    mapped = cli("xacro", RRBOT, "--package-path", str(EXAMPLES), "unused:=1")
    assert first.code == mapped.code == 0 and first.out == mapped.out
    assert "unused:=... is ignored" in mapped.err


def test_other_leftovers_are_still_errors(cli: Callable[..., ToolResult]) -> None:
    import pytest

    with pytest.raises(SystemExit) as caught:
        cli("xacro", RRBOT, "--package-path", str(EXAMPLES), "--bogus")
    assert caught.value.code == 2
