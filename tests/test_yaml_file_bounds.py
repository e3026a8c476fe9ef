"""Every YAML file a user names is read within bounds: size, nesting and alias expansion.

A 341-byte ``.rviz`` of nested aliases expands to 9^10 values, and 20,000 nested ``[`` overflow
PyYAML's recursive composer; each is refused with ``file:line:column`` and exit 2, before
anything is built.
"""

from __future__ import annotations

import itertools
import subprocess
from pathlib import Path

import pytest

from robomodel._yaml_bounded import YamlNestingError, check_yaml_file, load_yaml_file
from tests.conftest import EXAMPLES, ROBOMODEL
from tests.timing import scaled


def alias_bomb(levels: int = 9, width: int = 9) -> str:
    """``a: &a [x, ...]``, then each level a list of ``width`` aliases of the one before."""
    names = [chr(ord("a") + i) for i in range(levels + 1)]
    lines = [f"{names[0]}: &{names[0]} [{','.join('x' * width)}]"]
    for prev, name in itertools.pairwise(names):
        lines.append(f"{name}: &{name} [{','.join([f'*{prev}'] * width)}]")
    return "\n".join(lines) + "\n"


def test_an_alias_bomb_is_refused_where_it_passes_the_bound() -> None:
    text = alias_bomb()
    assert len(text) < 400
    with pytest.raises(YamlNestingError) as caught:
        check_yaml_file(text, where="bomb.rviz")
    error = caught.value
    assert (error.path, error.line) == ("bomb.rviz", 7)  # 9^7 > 10^6 values first on line 7
    assert str(error).startswith("bomb.rviz:7:")
    assert "more than 1000000 values once its aliases are expanded" in str(error)


def test_aliases_within_the_bounds_load_as_yaml_does() -> None:
    import yaml

    text = alias_bomb(levels=3, width=3)
    assert load_yaml_file(text, where="small.yaml") == yaml.safe_load(text)
    shared = "base: &b {p: 1, i: 2}\nleft: *b\nright: *b\n"
    assert load_yaml_file(shared, where="pid.yaml")["right"] == {"p": 1, "i": 2}


def test_nesting_is_bounded_directly_and_through_an_alias() -> None:
    check_yaml_file("[" * 100 + "]" * 100, where="ok.yaml")
    with pytest.raises(YamlNestingError, match=r"^deep.yaml:1:101: nested more than 100 levels"):
        check_yaml_file("[" * 101 + "]" * 101, where="deep.yaml")
    # 60 levels under an anchor, used 60 levels down: 120 once expanded.
    deep = "a: &a " + "[" * 60 + "]" * 60 + "\nb: " + "[" * 59 + "*a" + "]" * 59 + "\n"
    with pytest.raises(YamlNestingError, match=r"^alias.yaml:2:63: the alias \*a expands"):
        check_yaml_file(deep, where="alias.yaml")


def test_size_is_bounded() -> None:
    with pytest.raises(YamlNestingError, match=r"^big\.yaml: 2001 bytes, larger than the 2000"):
        check_yaml_file("a: " + "x" * 1998, where="big.yaml", max_bytes=2000)


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        (alias_bomb(), ":7:"),
        ("[" * 20000, ":1:"),
    ],
    ids=["alias-bomb", "nesting"],
)
def test_robomodel_view_refuses_a_hostile_rviz_file_with_one_line(
    tmp_path: Path, text: str, expected: str
) -> None:
    config = tmp_path / "hostile.rviz"
    config.write_text(text)
    result = subprocess.run(
        [*ROBOMODEL, "view", "-d", str(config), "--no-browser", "--port", "0",
         str(EXAMPLES / "gripper_description/urdf/planar_3dof.urdf")],
        capture_output=True, text=True, timeout=scaled(60),
    )  # fmt: skip
    assert result.returncode == 2, result.stderr
    [line] = result.stderr.strip().splitlines()
    assert line.startswith(f"robomodel: error: {config}{expected}"), line
    assert "invalid RViz config" in line


def test_controller_and_parameter_files_are_bounded(tmp_path: Path) -> None:
    from robomodel.control.config import load_controller_config
    from robomodel.control.exceptions import ConfigError
    from robomodel.launch.ros1.params import load_rosparam_yaml
    from robomodel.runtime.param_files import parameters_from_file
    from robomodel.runtime.params import load_parameters_file

    bomb = tmp_path / "bomb.yaml"
    bomb.write_text(alias_bomb())
    with pytest.raises(ConfigError) as caught:
        load_controller_config(bomb)
    assert caught.value.location is not None and caught.value.location.line == 7
    for read in (
        lambda: parameters_from_file(bomb, "/node"),
        lambda: load_parameters_file(bomb, "/node"),
        lambda: load_rosparam_yaml(bomb.read_text(), where=str(bomb)),
    ):
        with pytest.raises(Exception, match=rf"^{bomb}:7:\d+: more than 1000000 values"):
            read()


def test_xacro_kinematics_and_yaml_launch_files_are_bounded(tmp_path: Path) -> None:
    import robomodel.xacro as rx
    from robomodel.errors import InputError
    from robomodel.kinematics.yaml_model import read_kinematics_yaml
    from robomodel.launch.model import LaunchError
    from robomodel.launch.ros2.frontend.yaml_frontend import load_yaml_description

    bomb = tmp_path / "bomb.yaml"
    bomb.write_text(alias_bomb())
    robot = tmp_path / "r.xacro"
    robot.write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
        "<x v=\"${xacro.load_yaml('bomb.yaml')}\"/></robot>"
    )
    with pytest.raises(InputError, match=rf"load_yaml\('bomb.yaml'\): {bomb}:7:\d+: more than"):
        rx.process_file(robot)
    with pytest.raises(InputError) as caught:
        read_kinematics_yaml(str(bomb))
    assert caught.value.diagnostic.location.line == 7
    launch = tmp_path / "bomb.launch.yaml"
    launch.write_text(alias_bomb())
    with pytest.raises(LaunchError, match="more than 1000000 values") as raised:
        load_yaml_description(launch)
    assert raised.value.location is not None and raised.value.location.line == 7


def test_a_yaml_typed_launch_parameter_is_bounded() -> None:
    from robomodel.launch.ros1.params import ParamValueError, convert_value

    assert convert_value("[1, {a: 2}]", "yaml") == [1, {"a": 2}]
    with pytest.raises(ParamValueError, match=r"^invalid YAML: more than 1000000 values"):
        convert_value(alias_bomb(), "yaml")
