"""XML and YAML launch files: the frontend_demo corpus (launch_xml / launch_yaml semantics)."""

from __future__ import annotations

from pathlib import Path

import pytest

from robomodel.description.packages import PackageIndex
from robomodel.launch.model import LaunchError
from robomodel.launch.ros2 import load_launch
from tests.timing import scaled

from .conftest import CORPUS

XML = CORPUS / "frontend_demo/launch/talker.launch.xml"


def test_xml_node_namespace_remaps_params(corpus_index: PackageIndex) -> None:
    """push-ros-namespace + set_remap in a group, node params typed by YAML rules, nested
    params flattened with '.', value-sep lists, a param file with allow_substs, node env."""
    launch = load_launch(XML, packages=corpus_index)
    talker = launch.steps[0].node
    assert (talker.name, talker.namespace) == ("talker", "/robot1/")
    assert talker.args == ("--flag", "10", "a b")
    assert talker.remaps == (("chatter", "talk"), ("out", "/global_out"))
    values = [p.values for p in talker.parameters if p.values is not None]
    assert values == [
        {"use_sim_time": False}, {"rate": 10}, {"label": "hello"},
        {"gains.p": 1.5, "gains.i": 0}, {"names": ("a", "b")},
    ]  # fmt: skip
    substituted = talker.parameters[-1]
    assert substituted.allow_substs and "rate: 10" in substituted.file.read_text()
    assert talker.env == (("RCUTILS_COLORIZED_OUTPUT", "1"),)
    assert str(launch.steps[0].location).endswith("talker.launch.xml:12")


def test_xml_conditions_timers_and_scope(corpus_index: PackageIndex) -> None:
    """if/unless, absolute namespace, nested timers add up, the group's namespace is scoped."""
    launch = load_launch(XML, packages=corpus_index)
    kinds = [(s.kind, s.delay_s) for s in launch.steps]
    assert kinds == [
        ("node", 0.0),
        ("node", 0.0),
        ("process", 2.5),
        ("log", 3.5),
        ("node", 0.0),
        ("node", 0.0),
    ]
    assert (
        launch.steps[1].node.name == "plain_listener" and launch.steps[1].node.namespace == "/abs/"
    )
    assert launch.steps[2].command == ("echo", "robot1", "done")
    assert launch.steps[3].message == "after 10 s"
    sim = load_launch(XML, packages=corpus_index, args={"use_sim": "true", "ns": "r9"})
    assert sim.steps[1].node.name is None and sim.steps[1].node.namespace == "/"
    assert sim.steps[0].node.namespace == "/r9/"
    with pytest.raises(
        LaunchError, match=r"Argument \"use_sim\" provided value \"yes\" is not valid"
    ):
        load_launch(XML, packages=corpus_index, args={"use_sim": "yes"})


def test_yaml_include(corpus_index: PackageIndex) -> None:
    """An XML file includes a YAML one: args passed, typed params, unscoped group leaks."""
    launch = load_launch(XML, packages=corpus_index)
    child, leaked = launch.steps[4].node, launch.steps[5].node
    assert (child.name, child.namespace, child.remaps) == ("from_xml", "/kids/", (("a", "b"),))
    assert [p.values for p in child.parameters][1:] == [
        {"int_param": 3},
        {"str_param": "from_xml"},
        {"nested.leaf": 1.0},
    ]
    assert leaked.name == "yes"
    assert str(launch.steps[5].location).endswith("child.launch.yaml:32")
    assert launch.files[1].name == "child.launch.yaml"


def test_yaml_required_arg_missing(tmp_path: Path) -> None:
    """Including the YAML file without child_name fails naming the argument: as upstream, the
    top-level include already sees the nested required argument (statically), so the error
    points at its declaration."""
    (tmp_path / "top.launch.xml").write_text(
        f'<launch>\n  <include file="{CORPUS}/frontend_demo/launch/child.launch.yaml"/>\n</launch>\n'
    )
    with pytest.raises(
        LaunchError,
        match=r"child\.launch\.yaml:3: Included launch description missing required argument 'child_name' \(description: 'Name of the child node'\), given: \[\]",
    ):
        load_launch(tmp_path / "top.launch.xml")


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("<launch>\n<nodee pkg='a' exec='b'/>\n</launch>", r":2: unknown tag <nodee>"),
        (
            "<launch>\n<node pkg='a' exec='b' colour='red'/>\n</launch>",
            r":2: Unexpected attribute\(s\) found in `node`: colour",
        ),
        ("<launch>\n<node pkg='a'/>\n</launch>", r":2: <node> requires the attribute 'exec'"),
        (
            "<launch>\n<log message='$(var nope)'/>\n</launch>",
            r":2: launch configuration 'nope' does not exist",
        ),
        (
            "<launch>\n<log message='$(bogus x)'/>\n</launch>",
            r":2: unknown substitution '\$\(bogus\)'",
        ),
        ("<launch>\n<node_container pkg='a' exec='b' name='c'/>\n</launch>", r"not supported"),
        (
            "<launch>\n<node pkg='a' exec='b' if='maybe'/>\n</launch>",
            r":2: Unexpected condition expression 'maybe'",
        ),
    ],
)
def test_xml_errors(tmp_path: Path, text: str, message: str) -> None:
    """Errors name the element's line and what is wrong."""
    path = tmp_path / "bad.launch.xml"
    path.write_text(text)
    with pytest.raises(LaunchError, match=message):
        load_launch(path)


@pytest.mark.parametrize(
    "mode", [["--print"], ["--headless", "--bus", "inproc", "--duration", "0.5"]]
)
def test_temporary_parameter_files_are_removed_at_exit(tmp_path: Path, mode: list[str]) -> None:
    """The launch_params_*.yaml of ``allow_substs`` are gone when the launch
    ends (ros2 launch leaves them in /tmp; 11 piled up in one test session)."""
    import os
    import subprocess

    from tests.conftest import ROBOMODEL

    tmp = tmp_path / "tmp"
    tmp.mkdir()
    env = {**os.environ, "TMPDIR": str(tmp)}
    run = subprocess.run(
        [*ROBOMODEL, "launch", str(XML), "--package-path", str(CORPUS), *mode],
        capture_output=True, text=True, env=env, timeout=scaled(60),
    )  # fmt: skip
    assert run.returncode == 0, run.stderr
    assert not list(tmp.glob("launch_params_*")), sorted(p.name for p in tmp.iterdir())


def test_remove_temporary_files_of_the_python_api(corpus_index: PackageIndex) -> None:
    launch = load_launch(XML, packages=corpus_index)
    assert [p.name.startswith("launch_params_") for p in launch.temporary_files] == [True]
    assert all(p.exists() for p in launch.temporary_files)  # the nodes read them at start
    launch.remove_temporary_files()
    assert not any(p.exists() for p in launch.temporary_files)
