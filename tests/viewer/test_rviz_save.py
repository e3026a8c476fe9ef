"""The viewer opens a -d file that does not exist with RViz's defaults, and its
File folder saves what it shows; a launch whose rviz node names a missing file keeps running.
"""

from __future__ import annotations

import os
import shutil
import subprocess
from collections.abc import Iterator
from dataclasses import replace
from pathlib import Path

import pytest

from robomodel.viewer import RobotSource, Viewer, ViewerOptions
from robomodel.viewer.markup import escape_markdown
from robomodel.viewer.rviz_config import read_rviz_file
from robomodel.viewer.rviz_document import open_rviz_document
from robomodel.viewer.rviz_model import RvizDialect
from tests.conftest import EXAMPLES, ROBOMODEL
from tests.timing import scaled
from tests.viewer.conftest import wait_for
from tests.viewer.test_tools_inprocess import on_loop

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
    shown = {d.class_name: d for d in viewer.displays.displays}
    assert list(shown) == ["Grid", "RobotModel", "TF"]
    assert shown["TF"].option("Show Axes") and shown["RobotModel"].option("Visual Enabled")
    assert shown["RobotModel"].option("Description Topic") == "robot_description"  # RViz 1's
    wait_for(lambda: viewer.sessions[0].display.shown, what="the robot drawn")
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
    content = panel.status.content
    assert "Not saved" in content and escape_markdown(str(blocked / "x.rviz")) in content
    other = tmp_path / "other.rviz"
    tf = next(d for d in viewer.displays.displays if d.class_name == "TF")
    on_loop(viewer, lambda: tf.set_option("Show Names", True))  # TF > Show Names ticked
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
        capture_output=True, text=True, env=env, timeout=scaled(120),
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
        capture_output=True, text=True, env=env, timeout=scaled(120),
    )  # fmt: skip
    [line] = [x for x in result.stderr.splitlines() if "urdf.rviz" in x]
    assert line == (
        f"[/rviz] failed to start: {package}/urdf/urdf.rviz:2:1: invalid RViz config: "
        "did not find expected node content"
    )
    assert "Traceback" not in result.stderr


def test_the_readme_command_opens_a_missing_config_with_one_warning(tmp_path: Path) -> None:
    """The viewer reference's ``robomodel view ... -d urdf.rviz``, run in a fresh folder."""
    import shlex

    from tests.conftest import ROOT

    readme = (ROOT / "docs/reference/viewer.md").read_text()
    [line] = [x for x in readme.splitlines() if x.startswith("robomodel view ") and " -d " in x]
    argv = [str(ROOT / a) if a.startswith("examples/") else a for a in shlex.split(line)[2:]]
    result = subprocess.run(
        [*ROBOMODEL, "view", *argv, "--no-browser", "--port", "0", "--duration", "3"],
        capture_output=True, text=True, cwd=tmp_path, timeout=scaled(120),
    )  # fmt: skip
    assert result.returncode == 0, result.stderr
    assert "serving http://" in result.stdout
    warnings = [x for x in result.stderr.splitlines() if "warning" in x]
    assert warnings == [
        "robomodel view: warning: RViz config urdf.rviz does not exist: opening RViz's default "
        "displays (Grid) with RobotModel and TF; Save Config in the viewer writes it"
    ], result.stderr
    assert not (tmp_path / "urdf.rviz").exists()
    bad = tmp_path / "bad.rviz"
    bad.write_text("Panels: []\n")
    argv[argv.index("urdf.rviz")] = str(bad)
    result = subprocess.run(
        [*ROBOMODEL, "view", *argv, "--no-browser", "--port", "0", "--duration", "3"],
        capture_output=True, text=True, cwd=tmp_path, timeout=scaled(120),
    )  # fmt: skip
    assert result.returncode == 2 and "Traceback" not in result.stderr
    assert result.stderr.strip().endswith(
        "no 'Visualization Manager' section (is this a .rviz file?)"
    )


def test_a_ros2_launch_s_rviz2_with_a_missing_config_warns_once_and_runs(tmp_path: Path) -> None:
    launch = tmp_path / "view.launch.py"
    missing = tmp_path / "rviz" / "view.rviz"
    launch.write_text(
        "from launch import LaunchDescription\n"
        "from launch_ros.actions import Node\n\n\n"
        "def generate_launch_description():\n"
        "    return LaunchDescription([Node(package='rviz2', executable='rviz2',\n"
        f"                                   arguments=['-d', {str(missing)!r}])])\n"
    )
    result = subprocess.run(
        [*ROBOMODEL, "launch", str(launch), "--headless", "--bus", "inproc", "--duration", "2"],
        capture_output=True, text=True, timeout=scaled(120),
    )  # fmt: skip
    assert result.returncode == 0, result.stderr
    warnings = [x for x in result.stderr.splitlines() if "does not exist" in x]
    assert len(warnings) == 1 and str(missing) in warnings[0], result.stderr
    assert "failed to start" not in result.stderr


def test_a_ros2_document_saves_ros2_class_names(tmp_path: Path) -> None:
    """What a ROS 2 launch's rviz2 node opens for a missing file saves as RViz 2's classes."""
    from robomodel.viewer.rviz_state import config_with_state, implied_state
    from robomodel.viewer.rviz_write import write_rviz_config

    document, _ = open_rviz_document(str(tmp_path / "missing.rviz"), RvizDialect("ros2"))
    state = replace(implied_state(document), fixed_frame="odom")
    path = write_rviz_config(tmp_path / "saved.rviz", config_with_state(document, state))
    saved = read_rviz_file(path)
    assert saved.fixed_frame == "odom" and saved.dialect is RvizDialect.ROS2
    robot = saved.displays[1]
    assert robot.class_name == "rviz_default_plugins/RobotModel"
    assert robot.settings["Description Topic"]["Value"] == "/robot_description"
