"""Issue 27.1: the viewer opens a -d file that does not exist with RViz's defaults, and its
File folder saves what it shows; a launch whose rviz node names a missing file keeps running.
"""

from __future__ import annotations

import os
import shutil
import subprocess
from collections.abc import Iterator
from pathlib import Path

import pytest

from robomodel.viewer import RobotSource, Viewer, ViewerOptions
from robomodel.viewer.rviz_config import read_rviz_file
from robomodel.viewer.rviz_document import open_rviz_document
from robomodel.viewer.rviz_model import RvizDialect
from tests.conftest import EXAMPLES, ROBOMODEL

pytest.importorskip("viser")

PLANAR = EXAMPLES / "gripper_description/urdf/planar_3dof.urdf"


@pytest.fixture
def started() -> Iterator[list[Viewer]]:
    viewers: list[Viewer] = []
    yield viewers
    for viewer in viewers:
        viewer.close()


def _viewer(started: list[Viewer], path: Path, dialect: RvizDialect) -> Viewer:
    document, _ = open_rviz_document(str(path), dialect)
    viewer = Viewer(ViewerOptions(sources=(RobotSource(str(PLANAR)),), port=0, rviz=document))
    viewer.start()
    started.append(viewer)
    return viewer


def test_the_seed_step_add_robot_model_and_tf_set_the_fixed_frame_save(
    started: list[Viewer], tmp_path: Path
) -> None:
    """Seed 000: "urdf.rviz is not available, create it": the viewer shows Grid, RobotModel
    and TF; the fixed frame is set, Save Config writes urdf.rviz; opened again, it shows the
    same and saving again rewrites the same text."""
    path = tmp_path / "urdf" / "urdf.rviz"
    viewer = _viewer(started, path, RvizDialect.ROS1)
    panel = viewer.config_panel
    assert "does not exist yet" in panel.status.content
    assert viewer.tf_display.show_axes and viewer.display_options.show_visual
    viewer.fixed_dropdown.value = "link_1"
    assert panel.save(str(path)), panel.status.content
    assert str(path) in panel.status.content
    saved = read_rviz_file(path)
    assert saved.fixed_frame == "link_1"
    assert [(d.class_name, d.enabled) for d in saved.displays] == [
        ("rviz/Grid", True), ("rviz/RobotModel", True), ("rviz/TF", True),
    ]  # fmt: skip
    view = saved.view
    assert view is not None and view.class_name == "rviz/Orbit"
    camera = viewer.server.initial_camera  # robomodel's view, fitted to the robot
    assert view.settings["Distance"] == pytest.approx(
        sum((p - f) ** 2 for p, f in zip(camera.position, camera.look_at, strict=True)) ** 0.5,
        rel=1e-5,
    )
    text = path.read_text()
    viewer.close()
    again = _viewer(started, path, RvizDialect.ROS1)
    assert again.fixed_frame == "link_1"
    assert again.config_panel.save(str(path))
    assert path.read_text() == text


def test_save_config_as_and_an_unwritable_path(started: list[Viewer], tmp_path: Path) -> None:
    viewer = _viewer(started, tmp_path / "missing.rviz", RvizDialect.ROS2)
    panel = viewer.config_panel
    blocked = tmp_path / "a_file"
    blocked.write_text("")
    assert not panel.save(str(blocked / "x.rviz"))
    assert "Not saved" in panel.status.content and str(blocked / "x.rviz") in panel.status.content
    other = tmp_path / "other.rviz"
    viewer.options_panel.show_names.value = True  # TF > Show Names ticked in the page
    assert panel.save(str(other))
    assert panel.document.path == str(other)  # later saves go there, as RViz's do
    displays = read_rviz_file(other).displays
    classes = [d.class_name for d in displays]
    assert classes == [f"rviz_default_plugins/{k}" for k in ("Grid", "RobotModel", "TF")]
    assert displays[2].settings["Show Names"] is True


def _package_without_rviz(tmp_path: Path) -> Path:
    package = tmp_path / "gripper_description"
    shutil.copytree(EXAMPLES / "gripper_description", package)
    (package / "urdf/urdf.rviz").unlink()
    return package


def test_a_launch_whose_rviz_config_does_not_exist_keeps_running(tmp_path: Path) -> None:
    """Seed 000's display.launch before urdf.rviz exists: one warning, the nodes run."""
    package = _package_without_rviz(tmp_path)
    env = {**os.environ, "ROS_PACKAGE_PATH": str(tmp_path)}
    result = subprocess.run(
        [*ROBOMODEL, "launch", "gripper_description", "display.launch", "--headless",
         "--bus", "inproc", "--duration", "3"],
        capture_output=True, text=True, env=env, timeout=120,
    )  # fmt: skip
    assert result.returncode == 0, result.stderr
    warnings = [line for line in result.stderr.splitlines() if "urdf.rviz" in line]
    assert len(warnings) == 1 and "does not exist" in warnings[0], result.stderr
    assert "[/rviz] warning:" in warnings[0]
    assert "failed to start" not in result.stderr and "started /rviz" in result.stderr
    assert not (package / "urdf/urdf.rviz").exists()


def test_a_launch_whose_rviz_config_is_malformed_says_where(tmp_path: Path) -> None:
    package = _package_without_rviz(tmp_path)
    (package / "urdf/urdf.rviz").write_text("Visualization Manager: [\n")
    env = {**os.environ, "ROS_PACKAGE_PATH": str(tmp_path)}
    result = subprocess.run(
        [*ROBOMODEL, "launch", "gripper_description", "display.launch", "--headless",
         "--bus", "inproc", "--duration", "3"],
        capture_output=True, text=True, env=env, timeout=120,
    )  # fmt: skip
    assert f"{package}/urdf/urdf.rviz:" in result.stderr and "invalid RViz config" in result.stderr
    assert "Traceback" not in result.stderr
