"""``robomodel param`` against Debian's ``rosparam`` on the same ROS 1 master: seed 000's
sequence run once with each tool, the printed output and the resulting parameter tree compared.

The master is a real roscore, then robomodel's own: both tools must agree on either. The
roscore is one per module (each test empties its parameter server first); robomodel's side of
the sequence runs its command line's ``main`` in this process, as the printed output, the exit
codes and the tree are what is compared (tests/ros1wire/test_run_ros1.py and the error test
below run ``robomodel param`` as processes).
"""

from __future__ import annotations

import os
import subprocess
import xmlrpc.client
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import pytest

from robomodel.cli.main import main
from tests.conftest import ROBOMODEL
from tests.ros1wire.conftest import Ros1

Run = Callable[[list[str]], "subprocess.CompletedProcess[str]"]

# The module's roscore and master serve every test: one worker starts them once
pytestmark = pytest.mark.xdist_group("rosparam_cli")

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


def _transcript(ros1: Ros1, run: Run, work: Path) -> list[tuple[str, str, int]]:
    """Each step's stdout, stderr and exit code (an empty server at the start)."""
    _empty(ros1)
    out = []
    for step in _sequence(work):
        done = run(step)
        out.append((" ".join(step), done.stdout, done.returncode))
        if done.returncode != 0:
            out.append(("stderr", done.stderr.strip().splitlines()[-1], 0))
        if step[0] == "dump" and len(step) > 1:
            out.append(("file", Path(step[1]).read_text(), 0))
    return out


def _empty(ros1: Ros1) -> None:
    assert ros1.run(ROSPARAM, "delete", "/").returncode == 0


def _rosparam(ros1: Ros1, work: Path) -> Run:
    return lambda step: ros1.run(ROSPARAM, *step, cwd=work)


def _robomodel_param(
    ros1: Ros1, work: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> Run:
    """``robomodel param STEP`` by the command line's ``main`` in this process, in the
    environment and folder the tool processes get."""
    for name in [name for name in os.environ if name.startswith("ROS")]:
        monkeypatch.delenv(name)
    for name, value in ros1.env.items():
        monkeypatch.setenv(name, value)
    monkeypatch.chdir(work)

    def run(step: list[str]) -> subprocess.CompletedProcess[str]:
        capsys.readouterr()
        try:
            code = main(["param", *step])
        except SystemExit as stop:  # argparse's usage errors
            code = stop.code if isinstance(stop.code, int) else 1
        said = capsys.readouterr()
        return subprocess.CompletedProcess(["robomodel", "param", *step], code, said.out, said.err)

    return run


@pytest.fixture(scope="module")
def roscore_graph(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Ros1]:
    """One real roscore for the module's tests."""
    graph = Ros1(tmp_path_factory.mktemp("roscore"))
    try:
        graph.roscore()
        yield graph
    finally:
        graph.close()


@pytest.fixture(scope="module", params=["roscore", "robomodel"])
def graph(
    request: pytest.FixtureRequest, tmp_path_factory: pytest.TempPathFactory
) -> Iterator[Ros1]:
    """The module's roscore, or a ``robomodel master`` (module-scoped, so that both are set up
    before the function-scoped fixtures that check what a test left running)."""
    if request.param == "roscore":
        yield request.getfixturevalue("roscore_graph")
        return
    ros1 = Ros1(tmp_path_factory.mktemp("master"))
    try:
        ros1.robomodel("master", "--port", str(ros1.port))
        ros1.wait_for_master()
        yield ros1
    finally:
        ros1.close()


def test_param_on_a_ros1_master_equals_debian_s_rosparam(
    graph: Ros1,
    tmp_path: Path,
    capsys: pytest.CaptureFixture[str],
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    work = tmp_path / "work"
    work.mkdir()
    (work / "planar_3dof.urdf").write_text(URDF)

    reference = _transcript(graph, _rosparam(graph, work), work)
    reference_tree = _tree(graph)
    ours = _transcript(graph, _robomodel_param(graph, work, capsys, monkeypatch), work)
    assert ours == reference
    assert _tree(graph) == reference_tree
    # what the sequence must have left, so that two tools both doing nothing cannot agree
    assert reference_tree["color"] == [150, 55, 210]
    assert reference_tree["gain"] == {"p": 10, "d": 30}
    assert reference_tree["copy"] == {"p": 10, "i": 20, "d": 30}
    assert reference_tree["again"]["robot_description"] == URDF
    assert ("get /gain/i", "", 1) in ours


def test_param_errors_are_one_line(roscore_graph: Ros1, tmp_path: Path) -> None:
    ros1 = roscore_graph
    _empty(ros1)
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
