"""``name:=value`` may come after options, as roslaunch, ros2 launch and xacro accept it."""

from __future__ import annotations

import subprocess
from collections.abc import Callable

import pytest

from tests.conftest import EXAMPLES, ROBOMODEL, ToolResult
from tests.timing import scaled

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


@pytest.mark.parametrize(
    ("argv", "said"),
    [
        (["run", "--port", "99999999", "rviz", "rviz"],
         "argument --port: '99999999' is not a TCP port (0-65535"),
        (["run", "--bus", "inproc", "tf2_ros", "static_transform_publisher", "0", "0", "0", "0",
          "0", "0", "a", "b", "--ros-args", "-r", "__ns:=\x1b]0;owned\x07"],
         "robomodel: error: invalid namespace '/\\x1b]0;owned\\x07'"),
        (["run", "--bus", "inproc", "../../bin", "sh"], "unknown package '../../bin'"),
    ],
    ids=["port", "terminal-escape", "path"],
)  # fmt: skip
def test_hostile_run_arguments_are_one_line_and_exit_2(argv: list[str], said: str) -> None:
    """A port past 65535, a namespace that would retitle the terminal, a path for a package:
    one line, the control characters spelt out, exit 2."""
    done = subprocess.run([*ROBOMODEL, *argv], capture_output=True, text=True, timeout=scaled(60))
    assert done.returncode == 2, done.stderr
    assert said in done.stderr and "\x1b" not in done.stderr and "Traceback" not in done.stderr
