"""Ament resource-index markers, and a package that finds itself."""

from __future__ import annotations

import os
import shutil
import subprocess
from pathlib import Path

import pytest

from robomodel import xacro as rx
from robomodel.description.packages import PackageIndex
from robomodel.errors import PackageNotFoundError
from tests.conftest import EXAMPLES, ROBOMODEL
from tests.timing import scaled


def _ament_prefix_like_xacros_tests(tmp_path: Path, source: Path) -> Path:
    """xacro 2.1.1's test/CMakeLists.txt: a marker file, an empty share/<pkg>, a symlink."""
    prefix = tmp_path / "test_ament_index"
    marker = prefix / "share" / "ament_index" / "resource_index" / "packages" / "xacro"
    marker.parent.mkdir(parents=True)
    marker.write_text("")
    (prefix / "share" / "xacro").mkdir(parents=True)
    (prefix / "share" / "xacro" / "test").symlink_to(source)
    return prefix


def test_ament_marker_without_package_xml_is_found(tmp_path: Path) -> None:
    source = tmp_path / "src"
    source.mkdir()
    (source / "inner.xacro").write_text(
        '<a xmlns:xacro="http://www.ros.org/wiki/xacro"><b v="inner"/></a>'
    )
    prefix = _ament_prefix_like_xacros_tests(tmp_path, source)
    index = PackageIndex(environ={"AMENT_PREFIX_PATH": str(prefix)})
    assert index.find("xacro") == prefix / "share" / "xacro"
    assert index.get("xacro").origin == "AMENT_PREFIX_PATH"
    # What xacro's own tests do: include "$(find xacro)/test/inner.xacro".
    out = rx.process(
        '<a xmlns:xacro="http://www.ros.org/wiki/xacro">'
        '<xacro:include filename="$(find xacro)/test/inner.xacro"/></a>',
        package_index=index,
    )
    assert 'v="inner"' in out


def test_ament_markers_follow_prefix_order_and_skip_hidden(tmp_path: Path) -> None:
    first, second = tmp_path / "first", tmp_path / "second"
    for prefix in (first, second):
        markers = prefix / "share" / "ament_index" / "resource_index" / "packages"
        markers.mkdir(parents=True)
        (markers / "pkg").write_text("")
        (markers / ".hidden").write_text("")
    env = {"AMENT_PREFIX_PATH": f"{first}:{second}"}
    index = PackageIndex(environ=env)
    assert index.find("pkg") == first / "share" / "pkg"
    assert ".hidden" not in index.names()
    with pytest.raises(PackageNotFoundError):
        PackageIndex(environ={"AMENT_PREFIX_PATH": str(tmp_path / "nothing")}).find("pkg")


@pytest.fixture
def fresh_examples(tmp_path: Path) -> Path:
    """A copy of examples/ with no package path, as in a fresh clone."""
    copy = tmp_path / "clone" / "examples"
    shutil.copytree(EXAMPLES, copy)
    return copy


def _run(
    args: list[str], cwd: Path, extra_env: dict[str, str] | None = None
) -> subprocess.CompletedProcess[str]:
    env = {"PATH": "/usr/bin:/bin", "HOME": str(cwd), **(extra_env or {})}
    if "PYTHONPATH" in os.environ:  # the tree under test, not the installed one
        env["PYTHONPATH"] = os.environ["PYTHONPATH"]
    return subprocess.run(
        [*ROBOMODEL, *args], capture_output=True, text=True, cwd=cwd, env=env, timeout=scaled(120)
    )


@pytest.mark.parametrize(
    "verb",
    [
        ["xacro"],
        ["check"],
        ["graph", "-o", "out.dot"],
        ["fk", "--link", "ee_link"],
    ],
)
def test_every_verb_finds_the_inputs_own_package(fresh_examples: Path, verb: list[str]) -> None:
    # ur5.urdf.xacro includes $(find ur5_description)/urdf/ur5.xacro: its own package.
    path = "examples/ur5_description/urdf/ur5.urdf.xacro"
    run = _run([verb[0], path, *verb[1:]], fresh_examples.parent)
    assert run.returncode == 0, run.stderr
    assert "not found" not in run.stderr


def test_sibling_packages_of_the_workspace_are_found(tmp_path: Path) -> None:
    ws = tmp_path / "ws" / "src"
    for name in ("arm_description", "gripper_parts"):
        (ws / name / "urdf").mkdir(parents=True)
        (ws / name / "package.xml").write_text(f"<package><name>{name}</name></package>")
    (ws / "gripper_parts" / "urdf" / "g.xacro").write_text(
        '<r xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="finger"/></r>'
    )
    top = ws / "arm_description" / "urdf" / "arm.urdf.xacro"
    top.write_text(
        '<robot name="arm" xmlns:xacro="http://www.ros.org/wiki/xacro">'
        '<link name="base"/><xacro:include filename="$(find gripper_parts)/urdf/g.xacro"/>'
        "</robot>"
    )
    run = _run(["xacro", str(top)], tmp_path)
    assert run.returncode == 0, run.stderr
    assert '<link name="finger"/>' in run.stdout


def test_a_package_path_still_wins_over_the_workspace(tmp_path: Path) -> None:
    """For the input's neighbours: ``p`` beside the input's package ``top`` loses to the
    ``--package-path`` one."""
    ws = tmp_path / "ws"
    for root, value in ((ws / "src", "workspace"), (tmp_path / "other", "explicit")):
        (root / "p" / "urdf").mkdir(parents=True)
        (root / "p" / "package.xml").write_text("<package><name>p</name></package>")
        (root / "p" / "urdf" / "v.xacro").write_text(
            f'<r xmlns:xacro="http://www.ros.org/wiki/xacro"><x v="{value}"/></r>'
        )
    (ws / "src" / "top").mkdir()
    (ws / "src" / "top" / "package.xml").write_text("<package><name>top</name></package>")
    top = ws / "src" / "top" / "top.xacro"
    top.write_text(
        '<robot name="t" xmlns:xacro="http://www.ros.org/wiki/xacro">'
        '<xacro:include filename="$(find p)/urdf/v.xacro"/></robot>'
    )
    run = _run(["xacro", str(top), "--package-path", str(tmp_path / "other")], tmp_path)
    assert run.returncode == 0, run.stderr
    assert 'v="explicit"' in run.stdout


@pytest.mark.parametrize("where", ["beside", "ROS_PACKAGE_PATH", "--package-path"])
def test_a_files_own_package_wins_where_the_search_paths_know_none(
    tmp_path: Path, where: str
) -> None:
    """A copy of simplebot_description beside the original, with its
    simplebot_body.xacro broken, is processed with its own (broken) file. With the
    original on ROS_PACKAGE_PATH or --package-path, ROS's search finds the original, whichever
    file asks, and so does robomodel."""
    original = tmp_path / "aaa" / "simplebot_description"
    shutil.copytree(EXAMPLES / "simplebot_description", original)
    copy = tmp_path / "mine"
    shutil.copytree(EXAMPLES / "simplebot_description", copy)
    (copy / "urdf" / "simplebot_body.xacro").write_text("<robot><broken></robot>")
    args = ["xacro", str(copy / "urdf" / "simplebot.urdf.xacro")]
    env = {"ROS_PACKAGE_PATH": str(original.parent)} if where == "ROS_PACKAGE_PATH" else {}
    if where == "--package-path":
        args += ["--package-path", str(original.parent)]
    run = _run(args, tmp_path, env)
    if where == "beside":
        assert run.returncode == 2, run.stdout[:200]
        assert f"{copy}/urdf/simplebot_body.xacro:1:" in run.stderr
    else:
        assert run.returncode == 0, run.stderr
        assert "simplebot" in run.stdout


def test_package_not_found_says_where_and_how_in_user_terms(tmp_path: Path) -> None:
    """No internal path, the flags and variables that add a place, did-you-mean."""
    (tmp_path / "pkgs" / "gripper_description").mkdir(parents=True)
    (tmp_path / "pkgs" / "gripper_description" / "package.xml").write_text(
        "<package><name>gripper_description</name></package>"
    )
    launch = tmp_path / "t.launch"
    launch.write_text(
        '<launch>\n  <param name="x" textfile="$(find grippr_description)/a"/>\n</launch>'
    )
    run = _run(["launch", str(launch), "--dump-params"], tmp_path,
               {"ROS_PACKAGE_PATH": str(tmp_path / "pkgs")})  # fmt: skip
    assert run.returncode == 2
    lines = run.stderr.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in run.stderr, run.stderr
    line = lines[0]
    assert line.startswith(f"robomodel: error: {launch}:2:") or f"{launch}:2:" in line
    assert "did you mean 'gripper_description'" in line
    assert f"ROS_PACKAGE_PATH {tmp_path / 'pkgs'}" in line
    assert (
        "robomodel's built-in packages (foxglove_bridge, gazebo_ros, ros_gz_sim, rosbridge_server, xacro)"
        in line
    )
    assert "launch/share" not in line
    assert "--package-path DIR" in line and "ROS_PACKAGE_PATH=DIR" in line


def test_did_you_mean_for_packages_and_frames(fresh_examples: Path) -> None:
    bad = fresh_examples / "ur5_description" / "urdf" / "typo.urdf.xacro"
    bad.write_text(
        '<robot name="t" xmlns:xacro="http://www.ros.org/wiki/xacro">'
        '<xacro:include filename="$(find ur5_descriptin)/urdf/ur5.xacro"/></robot>'
    )
    run = _run(["xacro", str(bad)], fresh_examples.parent)
    assert run.returncode == 2
    assert "did you mean 'ur5_description'" in run.stderr
    urdf = "examples/gripper_description/urdf/planar_3dof.urdf"
    run = _run(["tf", urdf, "base_link", "grippr"], fresh_examples.parent)
    assert run.returncode == 2
    assert "Did you mean 'gripper'?" in run.stderr
    run = _run(["fk", urdf, "--link", "grippr"], fresh_examples.parent)
    assert run.returncode == 2 and "did you mean 'gripper'?" in run.stderr
