"""Every attribute value roslaunch 1.16's loader checks, against Debian's roslaunch.

Each case is loaded by ``roslaunch.xmlloader.XmlLoader.load_string`` (Debian's Python) and by
robomodel: both must accept it (with the same nodes) or both refuse it. ``if``/``unless`` take
roslaunch's loose ``convert_value(v, 'bool')`` (``1``/``0``, any case, blanks stripped);
``required``, ``respawn``, ``clear_params``, ``pass_all_args`` and ``subst_value`` take the
strict ``_bool_attr`` (``true``/``false`` only).
"""

from __future__ import annotations

import json
import subprocess
from pathlib import Path

import pytest

from robomodel.description.packages import PackageIndex
from robomodel.launch.model import LaunchError
from robomodel.launch.ros1 import load_launch
from tests.timing import scaled

_PROBE = """
import json, sys
import roslaunch.config, roslaunch.xmlloader
out = []
for xml in json.load(sys.stdin):
    config = roslaunch.config.ROSLaunchConfig()
    try:
        roslaunch.xmlloader.XmlLoader().load_string(xml, config, verbose=False)
        out.append(sorted(n.name for n in config.nodes))
    except Exception:
        out.append(None)
print(json.dumps(out))
"""

_BOOLS = ("true", "false", "TRUE", "False", "1", "0", " 1 ", " true", "yes", "2", "")


def _node(attrs: str = "", value: str | None = None) -> str:
    if value is not None:
        attrs = f'{attrs}="{value}"'
    return f'<node pkg="p" type="t" name="n" {attrs}/>'


def _cases() -> list[str]:
    cases = []
    for v in _BOOLS:
        cases += [
            f"<launch>{_node('if', v)}</launch>",
            f"<launch>{_node('unless', v)}</launch>",
            f'<launch><group if="{v}">{_node()}</group></launch>',
            f'<launch><arg name="a" value="1" unless="{v}"/>{_node()}</launch>',
            f"<launch>{_node('required', v)}</launch>",
            f"<launch>{_node('respawn', v)}</launch>",
            f'<launch><group ns="g" clear_params="{v}">{_node()}</group></launch>',
            f"<launch>{_node('clear_params', v)}</launch>",
            f'<launch><rosparam subst_value="{v}">a: 1</rosparam>{_node()}</launch>',
        ]
    for v in ("0", "1.5", "-1", "x", ""):
        cases.append(f"<launch>{_node('respawn_delay', v)}</launch>")
    for attrs in (
        'output="screen"',
        'output="log"',
        'output="Screen"',
        'output="both"',
        'output=""',
        'cwd=""',
        'cwd="node"',
        'cwd="ROS_HOME"',
        'cwd="ros_home"',
        'cwd="home"',
        'respawn="true" required="true"',
        'pkg=" "',
        'type=""',
    ):
        cases.append(f"<launch>{_node(attrs)}</launch>")
    machine = '<launch><machine name="m" address="localhost" {}="{}"/></launch>'
    for v in ("true", "false", "never", "TRUE", "Never", "yes", ""):
        cases.append(machine.format("default", v))
    for v in ("1", "0", "-2", "x", "", "2.5"):
        cases.append(machine.format("timeout", v))
    for v in ("22", "x"):
        cases.append(machine.format("ssh-port", v))
    test = '<launch><test test-name="t" pkg="p" type="t" {}="{}"/></launch>'
    for v in ("1", "0", "-1", "x", "", "2.5"):
        cases.append(test.format("time-limit", v))
    for v in ("1", "x", "", "-1"):
        cases.append(test.format("retry", v))
    return cases


def _reference(cases: list[str]) -> list[list[str] | None]:
    if not Path("/usr/lib/python3/dist-packages/roslaunch/xmlloader.py").exists():
        pytest.fail("Debian's roslaunch is missing: apt-get install python3-roslaunch")
    proc = subprocess.run(
        ["/usr/bin/python3", "-c", _PROBE],
        input=json.dumps(cases),
        capture_output=True,
        text=True,
        env={"PATH": "/usr/bin:/bin", "ROS_MASTER_URI": "http://localhost:11311"},
        timeout=scaled(120),
        check=True,
    )
    return json.loads(proc.stdout)  # type: ignore[no-any-return]


def _ours(tmp_path: Path, xml: str) -> list[str] | None:
    path = tmp_path / "case.launch"
    path.write_text(xml)
    try:
        launch = load_launch(path, packages=PackageIndex(use_environment=False), environ={})
    except LaunchError:
        return None
    return sorted(spec.name for spec in launch.nodes)


def test_attribute_values_match_roslaunch(tmp_path: Path) -> None:
    cases = _cases()
    reference = _reference(cases)
    mismatches = [
        (xml, ref, ours)
        for xml, ref in zip(cases, reference, strict=True)
        if (ours := _ours(tmp_path, xml)) != ref
    ]
    assert not mismatches, "\n".join(
        f"{x}\n  roslaunch {r}, robomodel {o}" for x, r, o in mismatches
    )


def test_unless_zero_from_optenv_runs_the_node(tmp_path: Path) -> None:
    """A real robot's launch file (husky): ``unless="$(optenv HUSKY_REALSENSE_ENABLED 0)"``."""
    xml = '<launch>\n  <node pkg="p" type="t" name="cam" unless="$(optenv HUSKY_RS 0)"/>\n</launch>'
    assert _ours(tmp_path, xml) == ["cam"]


def test_bad_if_value_names_the_file_line_and_the_valid_values(tmp_path: Path) -> None:
    path = tmp_path / "case.launch"
    path.write_text('<launch>\n  <node pkg="p" type="t" name="n" if="yes"/>\n</launch>')
    with pytest.raises(LaunchError) as info:
        load_launch(path, packages=PackageIndex(use_environment=False), environ={})
    message = str(info.value)
    assert message.startswith(f"{path}:2:")
    assert "'yes'" in message and "true, false, 1, 0" in message
