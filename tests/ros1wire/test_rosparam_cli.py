"""``robomodel param`` against Debian's ``rosparam`` on the same ROS 1 master: seed 000's
sequence run once with each tool, the printed output and the resulting parameter tree compared.

The master is a real roscore, then robomodel's own: both tools must agree on either.
"""

from __future__ import annotations

import xmlrpc.client
from pathlib import Path
from typing import Any

import pytest

from tests.conftest import ROBOMODEL
from tests.ros1wire.conftest import Ros1

ROSPARAM = "/usr/bin/rosparam"

URDF = """<?xml version="1.0"?>
<robot name="planar_3dof">
  <link name="base_link"/>
  <link name="link_1"/>
  <joint name="joint_1" type="revolute">
    <parent link="base_link"/> <child link="link_1"/>
    <limit lower="-1.57" upper="1.57" effort="0" velocity="0.5"/>
  </joint>
</robot>
"""


def _sequence(work: Path) -> list[list[str]]:
    """Seed 000's rosparam steps, then dump/load/delete/list and YAML typing corners."""
    dumped = str(work / "parameters.yaml")
    return [
        ["set", "/color", "[150,55,210]"],
        ["set", "/robot_description", "-t", "planar_3dof.urdf"],
        ["set", "/gain/p", "10"],
        ["set", "/gain/i", "20"],
        ["set", "/gain/d", "30"],
        ["get", "/gain"],
        ["get", "/gain/p"],
        ["get", "/color"],
        ["get", "/robot_description"],
        ["get", "-p", "/gain"],
        ["set", "/use_gui", "true"],
        ["set", "/offset", "-0.5"],
        ["set", "/angle", "deg(90)"],
        ["set", "/empty", ""],
        ["set", "/nested", "{a: {b: 1}, c: [x, 2.5]}"],
        ["get", "/nested"],
        ["dump", dumped],
        ["dump"],
        ["dump", str(work / "gain.yaml"), "/gain"],
        ["load", str(work / "gain.yaml"), "/copy"],
        ["load", dumped, "/again"],
        ["delete", "/gain/i"],
        ["get", "/gain/i"],
        ["delete", "/robot_description"],
        ["list"],
        ["list", "/copy"],
        ["get", "/again/gain"],
    ]


def _tree(ros1: Ros1) -> Any:
    with xmlrpc.client.ServerProxy(ros1.uri) as master:
        code, message, tree = master.getParam("/test", "/")
    assert code == 1, message
    return {k: v for k, v in tree.items() if k not in ("run_id", "rosdistro", "rosversion")}


def _transcript(ros1: Ros1, tool: list[str], work: Path) -> list[tuple[str, str, int]]:
    """Each step's stdout, stderr and exit code (an empty server at the start)."""
    assert ros1.run(ROSPARAM, "delete", "/").returncode == 0
    out = []
    for step in _sequence(work):
        done = ros1.run(*tool, *step, cwd=work)
        out.append((" ".join(step), done.stdout, done.returncode))
        if done.returncode != 0:
            out.append(("stderr", done.stderr.strip().splitlines()[-1], 0))
        if step[0] == "dump" and len(step) > 1:
            out.append(("file", Path(step[1]).read_text(), 0))
    return out


@pytest.mark.parametrize("master", ["roscore", "robomodel"])
def test_param_on_a_ros1_master_equals_debian_s_rosparam(
    ros1: Ros1, tmp_path: Path, master: str
) -> None:
    if master == "roscore":
        ros1.roscore()
    else:
        ros1.robomodel("master", "--port", str(ros1.port))
        ros1.until(lambda: ros1.run(ROSPARAM, "get", "/run_id").returncode == 0, "master")
    work = tmp_path / "work"
    work.mkdir()
    (work / "planar_3dof.urdf").write_text(URDF)

    reference = _transcript(ros1, [ROSPARAM], work)
    reference_tree = _tree(ros1)
    ours = _transcript(ros1, [*ROBOMODEL, "param"], work)
    assert ours == reference
    assert _tree(ros1) == reference_tree
    # what the sequence must have left, so that two tools both doing nothing cannot agree
    assert reference_tree["color"] == [150, 55, 210]
    assert reference_tree["gain"] == {"p": 10, "d": 30}
    assert reference_tree["copy"] == {"p": 10, "i": 20, "d": 30}
    assert reference_tree["again"]["robot_description"] == URDF
    assert ("get /gain/i", "", 1) in ours


def test_param_errors_are_one_line(ros1: Ros1, tmp_path: Path) -> None:
    ros1.roscore()
    missing = ros1.run(*ROBOMODEL, "param", "load", str(tmp_path / "nope.yaml"))
    assert missing.returncode == 2
    assert missing.stderr.strip().splitlines() == [
        f"robomodel: error: param load: file [{tmp_path / 'nope.yaml'}] does not exist"
    ]
    (tmp_path / "g.yaml").write_text("gain: {p: 1}\n")
    swapped = ros1.run(*ROBOMODEL, "param", "load", "/", str(tmp_path / "g.yaml"))
    assert swapped.returncode == 2
    assert f"did you mean `param load {tmp_path / 'g.yaml'} /`?" in swapped.stderr
    assert ros1.run(ROSPARAM, "get", "/gain").returncode == 1  # nothing was loaded
    folder = ros1.run(*ROBOMODEL, "param", "dump", "/")  # rosparam: IsADirectoryError
    assert folder.returncode == 2 and folder.stderr.strip().splitlines() == [
        "robomodel: error: param dump: '/' is a folder; dump takes a FILE first, then the "
        "namespace: `param dump params.yaml /` (or `param dump` to print them all)"
    ]
    big = ros1.run(*ROBOMODEL, "param", "set", "/big", "4294967296")
    assert big.returncode == 2 and "32-bit" in big.stderr
    assert ros1.run(ROSPARAM, "get", "/big").returncode == 1  # nothing was set
