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
    """Without dependencies: a catkin package whose manifest lists what its launch file runs."""
    result = cli("new", "arm_description", "--dir", str(tmp_path))
    assert result.code == 0
    assert result.out.startswith("Created catkin package ")
    pkg = tmp_path / "arm_description"
    for rel in (
        "package.xml",
        "CMakeLists.txt",
        "urdf/arm.urdf.xacro",
        "urdf/arm.urdf",
        "launch/display.launch",
        "config/joint_limits.yaml",
        "README.md",
        "meshes",
        "rviz",
    ):
        assert (pkg / rel).exists(), rel
    assert not (pkg / "launch" / "display.launch.py").exists()
    manifest = _debian_parse_package(pkg)
    assert manifest["format"] == 2 and manifest["buildtool_depends"] == ["catkin"]
    assert "robot_state_publisher" in manifest["exec_depends"] and not manifest["build_depends"]
    checked = cli("check", str(pkg / "urdf" / "arm.urdf"))
    assert checked.code == 0 and "warning" not in checked.out
    again = cli("new", "arm_description", "--dir", str(tmp_path))
    assert again.code == 2 and "already exists" in again.err


_PARSE_PACKAGE = """
import json, sys
from catkin_pkg.package import parse_package
p = parse_package(sys.argv[1])
p.validate()
names = lambda deps: [d.name for d in deps]
print(json.dumps({
    "name": p.name, "format": p.package_format, "description": p.description,
    "license": p.licenses, "maintainers": [m.name for m in p.maintainers],
    "buildtool_depends": names(p.buildtool_depends), "build_depends": names(p.build_depends),
    "build_export_depends": names(p.build_export_depends),
    "exec_depends": names(p.exec_depends), "test_depends": names(p.test_depends),
    "build_type": p.get_build_type(),
}))
"""


def _debian_parse_package(pkg: Path) -> dict[str, object]:
    """package.xml as Debian's catkin_pkg (python3-catkin-pkg) reads and validates it."""
    debian_python = Path("/usr/bin/python3")
    ok = subprocess.run([str(debian_python), "-c", "import catkin_pkg"], capture_output=True)
    if ok.returncode != 0:
        pytest.fail("catkin_pkg is not installed: apt-get install python3-catkin-pkg")
    proc = subprocess.run(
        [str(debian_python), "-c", _PARSE_PACKAGE, str(pkg)], capture_output=True, text=True
    )
    assert proc.returncode == 0, proc.stderr
    parsed: dict[str, object] = json.loads(proc.stdout)
    return parsed


def test_new_with_dependencies_writes_what_catkin_create_pkg_writes(
    cli: Callable[..., ToolResult], tmp_path: Path
) -> None:
    """The course's ``catkin_create_pkg gripper_description roscpp tf geometry_msgs urdf rviz
    xacro`` beside Debian's catkin_create_pkg: the same manifest (as catkin_pkg reads it), the
    same catkin COMPONENTS, the same include/ and src/ folders; plus the description folders."""
    deps = ["roscpp", "tf", "geometry_msgs", "urdf", "rviz", "xacro"]
    tool = shutil.which("catkin_create_pkg")
    if tool is None:
        pytest.fail("catkin_create_pkg is not installed: apt-get install python3-catkin-pkg")
    theirs, ours = tmp_path / "theirs", tmp_path / "ours"
    theirs.mkdir()
    ref = subprocess.run(
        [tool, "gripper_description", *deps], cwd=theirs, capture_output=True, text=True
    )
    assert ref.returncode == 0, ref.stderr
    result = cli("new", "gripper_description", *deps, "--dir", str(ours))
    assert result.code == 0, result.err
    ref_pkg, pkg = theirs / "gripper_description", ours / "gripper_description"
    assert _debian_parse_package(pkg) == _debian_parse_package(ref_pkg)
    assert _debian_parse_package(pkg)["build_depends"] == sorted(deps)

    def components(cmake: Path) -> str:
        text = cmake.read_text()
        start = text.index("\nfind_package(catkin")  # not the template's comments
        return text[start : text.index(")", start)]

    assert components(pkg / "CMakeLists.txt") == components(ref_pkg / "CMakeLists.txt")
    assert (pkg / "include" / "gripper_description").is_dir() and (pkg / "src").is_dir()
    for folder in ("urdf", "meshes", "launch", "rviz"):
        assert (pkg / folder).is_dir(), folder
    assert "DESTINATION ${CATKIN_PACKAGE_SHARE_DESTINATION}" in (pkg / "CMakeLists.txt").read_text()


def test_new_takes_ros2_pkg_create_arguments(
    cli: Callable[..., ToolResult], tmp_path: Path
) -> None:
    """``ros2 pkg create --build-type ament_cmake urdf_cpp_demo --dependencies rclcpp``: format 3,
    ``depend`` tags, ament_cmake build type and find_package, include/NAME and src/ as ros2pkg
    makes them, and the ROS 2 display launch file."""
    result = cli(
        "new", "--build-type", "ament_cmake", "urdf_cpp_demo", "--dependencies", "rclcpp",
        "--dir", str(tmp_path), "--license", "Apache-2.0", "-D", "URDF demo & loader",
    )  # fmt: skip
    assert result.code == 0, result.err
    pkg = tmp_path / "urdf_cpp_demo"
    manifest = _debian_parse_package(pkg)
    assert manifest["format"] == 3 and manifest["build_type"] == "ament_cmake"
    assert manifest["buildtool_depends"] == ["ament_cmake"]
    # <depend> is build, build export and exec dependency at once
    for kind in ("build_depends", "build_export_depends", "exec_depends"):
        assert manifest[kind] == ["rclcpp"], kind
    assert manifest["test_depends"] == ["ament_lint_auto", "ament_lint_common"]
    assert manifest["license"] == ["Apache-2.0"]
    assert manifest["description"] == "URDF demo &amp; loader"  # catkin_pkg keeps the markup
    cmake = (pkg / "CMakeLists.txt").read_text()
    assert "find_package(rclcpp REQUIRED)" in cmake and "ament_package()" in cmake
    assert (pkg / "launch" / "display.launch.py").exists()
    assert not (pkg / "launch" / "display.launch").exists()
    assert (pkg / "include" / "urdf_cpp_demo").is_dir() and (pkg / "src").is_dir()
    # --dependencies alone means ros2 pkg create, so ament_cmake
    implied = cli("new", "b_description", "--dependencies", "urdf", "--dir", str(tmp_path))
    assert implied.out.startswith("Created ament_cmake package ")


@pytest.mark.parametrize(
    "argv",
    [["arm", "Not-A-Package"], ["arm", "--build-type", "ament_python"], ["arm", "--bogus"]],
    ids=["bad dependency", "unsupported build type", "unknown option"],
)
def test_new_rejects_bad_arguments(tmp_path: Path, argv: list[str]) -> None:
    proc = subprocess.run(
        [sys.executable, "-m", "robomodel.cli.main", "new", *argv, "--dir", str(tmp_path)],
        capture_output=True,
        text=True,
    )
    assert proc.returncode == 2 and "Traceback" not in proc.stderr
    assert proc.stderr.strip().splitlines()[-1].startswith("robomodel")
    assert list(tmp_path.iterdir()) == []


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
