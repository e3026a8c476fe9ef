"""The UR5 example draws ur_description's meshes from example-robot-data, and falls
back to its collision cylinders, with one status line, where that package is not found."""

from __future__ import annotations

from pathlib import Path

import pytest

from robomodel.description.packages import PackageIndex, example_robot_data_packages
from robomodel.loading import read_description
from robomodel.viewer.meshes import MeshCache
from robomodel.viewer.status import RobotStatus, render_status
from tests.conftest import EXAMPLES, example_robot_data_dir

UR5 = EXAMPLES / "ur5_description" / "urdf" / "ur5_robot.urdf.xacro"
_ARM_LINKS = {"base_link", "shoulder_link", "upper_arm_link", "forearm_link", "wrist_1_link",
              "wrist_2_link", "wrist_3_link"}  # fmt: skip


def test_example_robot_data_folders_are_packages() -> None:
    index = PackageIndex(environ={})
    assert index.find("ur_description") == example_robot_data_dir() / "ur_description"
    assert index.get("ur_description").origin == "example-robot-data"
    assert index.find("example-robot-data") == example_robot_data_dir().parent
    seed_uri = "package://ur_description/meshes/ur5/visual/base.dae"
    assert index.resolve(seed_uri).is_file()
    names = {name for name, _ in example_robot_data_packages()}
    assert {"panda_description", "ur_description"} <= names


def test_a_users_own_package_of_the_same_name_wins(tmp_path: Path) -> None:
    own = tmp_path / "src" / "ur_description"
    own.mkdir(parents=True)
    (own / "package.xml").write_text("<package><name>ur_description</name></package>")
    for environ in ({"ROS_PACKAGE_PATH": str(tmp_path / "src")}, {}):
        paths = [] if environ else [tmp_path / "src"]
        index = PackageIndex(package_paths=paths, environ=environ)
        assert index.find("ur_description") == own


def test_the_switch_and_use_environment_turn_it_off() -> None:
    off = PackageIndex(environ={"ROBOMODEL_EXAMPLE_ROBOT_DATA": "0"})
    assert "ur_description" not in off.names()
    assert "ur_description" not in PackageIndex(use_environment=False).names()
    assert "ur_description" in PackageIndex(use_environment=False, example_robot_data=True).names()


def _display(index: PackageIndex) -> tuple[object, object]:
    import viser

    from robomodel.viewer.scene import RobotModelDisplay

    parsed, _ = read_description(UR5, package_index=index.with_workspace_of(UR5))
    robot = parsed.robot
    server = viser.ViserServer(host="127.0.0.1", port=0, verbose=False)
    display = RobotModelDisplay(
        server.scene, "/robots/0", robot, index=index, base_dir=UR5.parent, meshes=MeshCache()
    )
    display.build()
    display.load_meshes()
    return server, display


def test_the_ur5_example_draws_the_meshes_with_example_robot_data() -> None:
    pytest.importorskip("viser")
    server, display = _display(PackageIndex(environ={}))
    try:
        assert display.problems == []  # type: ignore[attr-defined]
        assert display.substituted == []  # type: ignore[attr-defined]
        drawn = {name.split("/")[3] for name in display.mesh_nodes}  # type: ignore[attr-defined]
        assert len(drawn) == len(_ARM_LINKS)  # one visual mesh per arm link
    finally:
        server.stop()  # type: ignore[attr-defined]


def test_the_ur5_example_falls_back_to_cylinders_with_one_status_line() -> None:
    pytest.importorskip("viser")
    server, display = _display(PackageIndex(environ={"ROBOMODEL_EXAMPLE_ROBOT_DATA": "0"}))
    try:
        assert display.problems == []  # type: ignore[attr-defined]
        assert display.mesh_nodes == []  # type: ignore[attr-defined]
        substituted = display.substituted  # type: ignore[attr-defined]
        assert {link for _, link in substituted} == _ARM_LINKS
        assert {package for package, _ in substituted} == {"ur_description"}
        shown = [
            g
            for g in display._groups["visual"]  # type: ignore[attr-defined]
            if g.name.rsplit("/", 1)[-1].startswith("s")
        ]
        assert len(shown) == len(_ARM_LINKS)  # a cylinder each, in the Visual group
        status = RobotStatus(
            label="ur5", path=str(UR5), failure=None, problems=(), missing_frames=(),
            fixed_frame="world", placed_beside=False, pending_meshes=0,
            substituted=tuple(substituted),
        )  # fmt: skip
        text = render_status([status], True, "world")
        assert text.count("\n") == 0
        assert "package `ur_description` not found: 7 link(s) drawn with their collision" in text
        assert "pip install example-robot-data" in text
    finally:
        server.stop()  # type: ignore[attr-defined]
