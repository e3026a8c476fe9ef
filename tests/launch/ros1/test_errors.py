"""Bad launch files: one clear error with file:line:column and the include stack."""

from __future__ import annotations

from pathlib import Path

import pytest

from robomodel.description.packages import PackageIndex
from robomodel.launch.model import LaunchError
from robomodel.launch.ros1 import load_launch


def _load(tmp_path: Path, text: str, name: str = "t.launch", **kw: object) -> object:
    path = tmp_path / name
    path.write_text(text)
    return load_launch(path, packages=PackageIndex(use_environment=False), **kw)  # type: ignore[arg-type]


def _error(tmp_path: Path, text: str, **kw: object) -> LaunchError:
    with pytest.raises(LaunchError) as info:
        _load(tmp_path, text, **kw)
    return info.value


def test_missing_required_arg_names_it(tmp_path: Path) -> None:
    error = _error(
        tmp_path,
        '<launch>\n  <arg name="model"/>\n  <param name="m" value="$(arg model)"/>\n</launch>',
    )
    assert "requires the 'model' arg to be set" in str(error)


def test_unknown_package_with_location_and_hint(tmp_path: Path) -> None:
    (tmp_path / "gripper_description").mkdir()
    (tmp_path / "gripper_description" / "package.xml").write_text(
        "<package><name>gripper_description</name></package>"
    )
    text = '<launch>\n  <param name="x" textfile="$(find gripper_descripton)/a.urdf"/>\n</launch>'
    path = tmp_path / "t.launch"
    path.write_text(text)
    with pytest.raises(LaunchError) as info:
        load_launch(path, packages=PackageIndex(package_paths=[tmp_path], use_environment=False))
    message = str(info.value)
    assert message.startswith(f"{path}:2:")
    assert "gripper_descripton" in message and "did you mean 'gripper_description'" in message


def test_xml_error_has_line_and_column(tmp_path: Path) -> None:
    error = _error(tmp_path, "<launch>\n  <param name='x' value='1'>\n</launch>")
    assert error.location is not None and error.location.line == 3
    assert "Invalid roslaunch XML syntax" in error.message


def test_missing_file_and_include_stack(tmp_path: Path) -> None:
    inner = tmp_path / "inner.launch"
    inner.write_text('<launch>\n  <include file="$(dirname)/missing.launch"/>\n</launch>')
    error = _error(
        tmp_path, f'<launch>\n  <include file="{inner}"/>\n</launch>', name="outer.launch"
    )
    text = str(error)
    assert f"{inner}:2:" in text and "cannot read launch file" in text
    assert f"included from {tmp_path / 'outer.launch'}:2:" in text


def test_bad_yaml_points_into_the_yaml_file(tmp_path: Path) -> None:
    (tmp_path / "bad.yaml").write_text("a: 1\nb: [1, 2\n")
    error = _error(tmp_path, f'<launch>\n  <rosparam file="{tmp_path / "bad.yaml"}"/>\n</launch>')
    assert error.location is not None and error.location.path == str(tmp_path / "bad.yaml")
    assert error.include_stack and error.include_stack[-1].line == 2


def test_failing_command(tmp_path: Path) -> None:
    error = _error(tmp_path, '<launch>\n  <param name="x" command="false"/>\n</launch>')
    assert "returned with code [1]" in str(error) and ":2:" in str(error)


def test_xacro_error_keeps_its_location(tmp_path: Path) -> None:
    (tmp_path / "bad.xacro").write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n  <link name="${nope}"/>\n</robot>'
    )
    error = _error(
        tmp_path,
        f'<launch>\n  <param name="robot_description" command="xacro {tmp_path / "bad.xacro"}"/>\n</launch>',
    )
    assert f"{tmp_path / 'bad.xacro'}:2:" in str(error) and "nope" in str(error)


def test_unused_include_arg(tmp_path: Path) -> None:
    (tmp_path / "inc.launch").write_text("<launch/>")
    error = _error(
        tmp_path,
        f'<launch>\n  <include file="{tmp_path / "inc.launch"}">\n    <arg name="x" value="1"/>\n  </include>\n</launch>',
    )
    assert "unused args [x]" in str(error)


@pytest.mark.parametrize(
    "expr",
    [
        "().__class__",
        "__import__('os')",
        "[c for c in ().__class__.__mro__]",
        "open('/etc/passwd')",
    ],
)
def test_eval_is_refused_like_xacro(tmp_path: Path, expr: str) -> None:
    error = _error(tmp_path, f'<launch>\n  <param name="x" value="$(eval {expr})"/>\n</launch>')
    assert "eval" in str(error)


def test_entity_bomb_is_refused(tmp_path: Path) -> None:
    bomb = '<?xml version="1.0"?>\n<!DOCTYPE l [<!ENTITY a "aaaa">]>\n<launch><param name="x" value="&a;"/></launch>'
    error = _error(tmp_path, bomb)
    assert "entity declarations are not allowed" in str(error)


def test_root_must_be_launch(tmp_path: Path) -> None:
    error = _error(tmp_path, "<robot name='r'/>")
    assert "no root <launch> tag" in str(error)
