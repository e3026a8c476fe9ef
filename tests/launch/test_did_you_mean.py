"""What a new user mistypes gets a did-you-mean (a verb, a launch file in a
package), and a ``name:=value`` that no launch ``<arg>`` or ``<xacro:arg>`` declares gets a
warning naming the declared ones (ROS ignores it silently and so does robomodel, apart from the
warning)."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

from tests.conftest import EXAMPLES, ToolResult

Cli = Callable[..., ToolResult]


def test_mistyped_verb(cli: Cli) -> None:
    result = cli("lanch", "gripper_description", "display.launch")
    assert result.code == 2
    assert result.err.startswith(
        "robomodel: error: unknown command 'lanch' (did you mean 'launch'?)"
    )
    assert "usage:" not in result.err and len(result.err.strip().splitlines()) == 1


def test_mistyped_launch_file_in_a_package(cli: Cli) -> None:
    result = cli("launch", "--package-path", str(EXAMPLES), "gripper_description", "displey.launch")
    assert result.code == 2
    assert "did you mean 'display.launch'" in result.err
    assert "launch files in gripper_description: display.launch, display_xacro.launch" in result.err


def test_undeclared_ros1_launch_argument_warns_and_runs_on(cli: Cli, tmp_path: Path) -> None:
    inner = tmp_path / "inner.launch"
    inner.write_text(
        '<launch>\n  <arg name="deep"/>\n  <param name="d" value="$(arg deep)"/>\n</launch>'
    )
    top = tmp_path / "top.launch"
    top.write_text(
        '<launch>\n  <arg name="model" default="a"/>\n'
        f'  <include file="{inner}" pass_all_args="true"/>\n</launch>'
    )
    result = cli("launch", str(top), "modle:=b", "deep:=1", "--nodes")
    assert result.code == 0, result.err
    warnings = [line for line in result.err.splitlines() if "warning" in line]
    assert len(warnings) == 1, result.err  # deep:= is declared by the included file
    assert warnings[0].startswith(f"{top}: warning: launch argument modle:=")
    assert "(did you mean 'model'?)" in warnings[0]
    assert "declared arguments: model, deep" in warnings[0]


def test_undeclared_ros2_launch_argument_warns(cli: Cli, tmp_path: Path) -> None:
    top = tmp_path / "top.launch.yaml"
    top.write_text("launch:\n  - arg: {name: use_gui, default: 'false'}\n")
    result = cli("launch", str(top), "use_giu:=true", "--show-args")
    assert result.code == 0, result.err
    assert "launch argument use_giu:=... is not declared" in result.err
    assert "(did you mean 'use_gui'?)" in result.err
    assert cli("launch", str(top), "use_gui:=true", "--show-args").err == ""


def test_undeclared_xacro_arg_warns(cli: Cli) -> None:
    path = EXAMPLES / "ur5_description" / "urdf" / "ur5.urdf.xacro"
    result = cli("xacro", str(path), "prefx:=left_")
    assert result.code == 0 and "<robot" in result.out
    assert f"{path}: warning: prefx:=... is ignored" in result.err
    assert "(did you mean 'prefix'?)" in result.err and "declared args: prefix" in result.err
    assert "warning" not in cli("xacro", str(path), "prefix:=left_").err
