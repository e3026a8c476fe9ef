"""The check, graph and new verbs end to end."""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
from collections.abc import Callable
from pathlib import Path

import pytest

from tests.conftest import EXAMPLES, ToolResult

PLANAR = EXAMPLES / "gripper_description" / "urdf" / "planar_3dof.urdf"


def test_check_planar_3dof_matches_the_course(cli: Callable[..., ToolResult]) -> None:
    result = cli("check", str(PLANAR))
    assert result.code == 0
    assert result.out == (
        "robot name is: planar_3dof\n"
        "---------- Successfully Parsed XML ---------------\n"
        "root Link: base_link has 1 child(ren)\n"
        "    child(1):  link_1\n"
        "        child(1):  link_2\n"
        "            child(1):  gripper\n"
    )


def test_check_json(cli: Callable[..., ToolResult], tmp_path: Path) -> None:
    result = cli("check", "--json", str(PLANAR))
    payload = json.loads(result.out)
    assert payload["valid"] and payload["root"] == "base_link" and payload["links"] == 4
    bad = tmp_path / "bad.urdf"
    bad.write_text('<robot name="r">\n<link name="a"/>\n<link name="a"/>\n</robot>')
    result = cli("check", "--json", str(bad))
    payload = json.loads(result.out)
    assert result.code == 2 and not payload["valid"]
    assert payload["diagnostics"][0]["line"] == 3
    assert payload["diagnostics"][0]["code"] == "duplicate-link"


def test_check_resolves_packages(cli: Callable[..., ToolResult], tmp_path: Path) -> None:
    pkg = tmp_path / "pkg"
    (pkg / "meshes").mkdir(parents=True)
    (pkg / "package.xml").write_text("<package format='3'><name>mypkg</name></package>")
    (pkg / "meshes" / "a.stl").write_text("solid a\nendsolid a\n")
    urdf = tmp_path / "r.urdf"
    urdf.write_text(
        '<robot name="r"><link name="a"><visual><geometry>'
        '<mesh filename="package://mypkg/meshes/a.stl"/></geometry></visual></link></robot>'
    )
    assert "does not resolve" in cli("check", str(urdf)).out
    found = cli("check", str(urdf), "--package-path", str(tmp_path))
    assert found.code == 0 and "warning" not in found.out
    explicit = cli("check", str(urdf), "--package", f"mypkg={pkg}")
    assert explicit.code == 0 and "warning" not in explicit.out


def test_graph_gv_to_stdout(cli: Callable[..., ToolResult]) -> None:
    result = cli("graph", str(PLANAR), "-o", "-")
    assert result.code == 0
    assert result.out.startswith('digraph G {\nnode [shape=box];\n"base_link" [label="base_link"];')
    assert '"link_1" -> "joint_2" [label="xyz: 0.5 0 0 \\nrpy: 0 -0 0"]' in result.out


@pytest.mark.parametrize("suffix", [".svg", ".pdf", ".png", ".gv"])
def test_graph_rendered(cli: Callable[..., ToolResult], tmp_path: Path, suffix: str) -> None:
    out = tmp_path / "sub" / f"planar{suffix}"
    result = cli("graph", str(PLANAR), "-o", str(out))
    assert result.code == 0 and out.exists()
    data = out.read_bytes()
    magic = {".svg": b"<?xml", ".pdf": b"%PDF", ".png": b"\x89PNG", ".gv": b"digraph"}[suffix]
    assert data.startswith(magic)
    assert [p.name for p in out.parent.iterdir()] == [out.name]  # no temp files left


def test_graph_without_output_writes_what_urdf_to_graphviz_writes(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """``urdf_to_graphviz FILE`` (Debian's liburdfdom-tools) writes ``$ROBOT_NAME.gv`` and
    ``$ROBOT_NAME.pdf`` in the current folder and names both; so does ``robomodel graph FILE``."""
    if shutil.which("dot") is None:
        pytest.skip("Graphviz's dot renders the pdf")
    reference = shutil.which("urdf_to_graphviz")
    if reference is None:
        pytest.fail("urdf_to_graphviz is not installed: apt-get install liburdfdom-tools")
    theirs, ours = tmp_path / "theirs", tmp_path / "ours"
    theirs.mkdir()
    ours.mkdir()
    ref = subprocess.run([reference, str(PLANAR)], cwd=theirs, capture_output=True, text=True)
    assert ref.returncode == 0, ref.stderr
    run = subprocess.run(
        [sys.executable, "-m", "robomodel.cli.main", "graph", str(PLANAR)],
        cwd=ours,
        capture_output=True,
        text=True,
    )
    assert run.returncode == 0, run.stderr
    assert run.stdout == ref.stdout == "Created file planar_3dof.gv\nCreated file planar_3dof.pdf\n"
    assert sorted(p.name for p in ours.iterdir()) == ["planar_3dof.gv", "planar_3dof.pdf"]
    assert sorted(p.name for p in theirs.iterdir()) == ["planar_3dof.gv", "planar_3dof.pdf"]
    assert (ours / "planar_3dof.gv").read_text() == (theirs / "planar_3dof.gv").read_text()
    assert (ours / "planar_3dof.pdf").read_bytes().startswith(b"%PDF")


def test_graph_without_output_or_dot_keeps_the_gv(
    cli: Callable[..., ToolResult], tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(shutil, "which", lambda name: None)
    result = cli("graph", str(PLANAR))
    assert result.code == 2 and "apt-get install graphviz" in result.err
    assert result.out == "Created file planar_3dof.gv\n"
    assert [p.name for p in tmp_path.iterdir()] == ["planar_3dof.gv"]


def test_graph_without_dot_names_the_package(
    cli: Callable[..., ToolResult], tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(shutil, "which", lambda name: None)
    result = cli("graph", str(PLANAR), "-o", str(tmp_path / "g.svg"))
    assert result.code == 2 and "apt-get install graphviz" in result.err
    assert not (tmp_path / "g.svg").exists()


def test_new_package_passes_check(cli: Callable[..., ToolResult], tmp_path: Path) -> None:
    result = cli("new", "arm_description", "--dir", str(tmp_path))
    assert result.code == 0
    pkg = tmp_path / "arm_description"
    for rel in (
        "package.xml",
        "CMakeLists.txt",
        "urdf/arm.urdf.xacro",
        "urdf/arm.urdf",
        "launch/display.launch.py",
        "launch/display.launch",
        "config/joint_limits.yaml",
        "README.md",
        "meshes",
    ):
        assert (pkg / rel).exists(), rel
    assert '<package format="3">' in (pkg / "package.xml").read_text()
    assert "<exec_depend>robot_state_publisher</exec_depend>" in (pkg / "package.xml").read_text()
    checked = cli("check", str(pkg / "urdf" / "arm.urdf"))
    assert checked.code == 0 and "warning" not in checked.out
    again = cli("new", "arm_description", "--dir", str(tmp_path))
    assert again.code == 2 and "already exists" in again.err


def test_new_xacro_expands_to_the_plain_urdf(tmp_path: Path) -> None:
    """The scaffold's xacro and its plain twin describe the same robot (reference xacro)."""
    import xacro  # the reference xacro 2.1.1, from the test extra

    from robomodel.description import read_urdf
    from robomodel.description.scaffold import create_description_package

    pkg = create_description_package("twin_description", tmp_path)
    doc = xacro.process_file(str(pkg / "urdf" / "twin.urdf.xacro"))
    expanded = read_urdf(doc.toxml()).robot
    plain = read_urdf(pkg / "urdf" / "twin.urdf").robot
    assert expanded == plain


@pytest.mark.parametrize("name", ["Bad-Name", "1robot", "has space", ""])
def test_new_rejects_invalid_names(
    cli: Callable[..., ToolResult], tmp_path: Path, name: str
) -> None:
    result = cli("new", name, "--dir", str(tmp_path))
    assert result.code == 2 and "valid ROS package name" in result.err
    assert list(tmp_path.iterdir()) == []


def test_console_script_runs() -> None:
    exe = Path(sys.executable).parent / "robomodel"
    proc = subprocess.run([str(exe), "check", str(PLANAR)], capture_output=True, text=True)
    assert proc.returncode == 0 and proc.stdout.startswith("robot name is: planar_3dof")


def test_unknown_package_reported_once(cli: Callable[..., ToolResult], tmp_path: Path) -> None:
    visuals = "".join(
        f'<visual><geometry><mesh filename="package://ghost/m{i}.stl"/></geometry></visual>'
        for i in range(3)
    )
    urdf = tmp_path / "r.urdf"
    urdf.write_text(f'<robot name="r">\n<link name="a">\n{visuals}\n</link>\n</robot>')
    result = cli("check", str(urdf))
    assert result.code == 0
    assert result.out.count("package 'ghost' not found") == 1
    assert "2 more meshes use the unknown package 'ghost'" in result.out


def test_outputs_get_normal_permissions(cli: Callable[..., ToolResult], tmp_path: Path) -> None:
    import os

    for name in ("g.svg", "g.gv"):
        cli("graph", str(PLANAR), "-o", str(tmp_path / name))
        mask = os.umask(0)
        os.umask(mask)
        assert (tmp_path / name).stat().st_mode & 0o777 == 0o666 & ~mask
