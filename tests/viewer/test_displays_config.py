"""Displays in .rviz configs, in this process: every display of a -d file opens in the Displays
panel with its options (ROS 1 and ROS 2 forms), a class robomodel lacks is listed with RViz's
status, and Save writes every display back (unchanged ones byte for byte)."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest
import yaml

from robomodel.viewer import RobotSource, Viewer, ViewerOptions
from robomodel.viewer.displays import StatusLevel
from robomodel.viewer.markup import escape_markdown
from robomodel.viewer.rviz_config import read_rviz_file
from robomodel.viewer.rviz_document import open_rviz_document
from robomodel.viewer.rviz_model import RvizDialect
from tests.conftest import EXAMPLES
from tests.viewer.conftest import wait_for
from tests.viewer.test_tools_inprocess import on_loop

pytest.importorskip("viser")

PLANAR = EXAMPLES / "gripper_description/urdf/planar_3dof.urdf"

ROS2_CONFIG = """\
Panels:
  - Class: rviz_common/Displays
    Name: Displays
Visualization Manager:
  Class: ""
  Displays:
    - Class: rviz_default_plugins/Grid
      Enabled: true
      Name: Grid
      Value: true
    - Class: rviz_default_plugins/Marker
      Enabled: true
      Name: Obstacles
      Namespaces:
        walls: true
      Topic:
        Depth: 7
        Durability Policy: Volatile
        History Policy: Keep Last
        Reliability Policy: Reliable
        Value: /obstacles
      Value: true
    - Class: rviz_default_plugins/DepthCloud
      Enabled: true
      Name: Depth
      Topic: /depth
      Value: true
    - Class: rviz_default_plugins/MarkerArray
      Enabled: false
      Name: Plans
      Namespaces:
        path: false
      Topic:
        Depth: 5
        Durability Policy: Transient Local
        History Policy: Keep Last
        Reliability Policy: Reliable
        Value: /plans
      Value: false
    - Class: rviz_plugin_tutorials/Imu
      Enabled: true
      Name: Imu
      Value: true
  Global Options:
    Fixed Frame: base_link
"""


@pytest.fixture
def started() -> Iterator[list[Viewer]]:
    viewers: list[Viewer] = []
    yield viewers
    for viewer in viewers:
        viewer.close()


def _viewer(started: list[Viewer], path: Path, dialect: RvizDialect = RvizDialect.ROS2) -> Viewer:
    document, _ = open_rviz_document(str(path), dialect)
    viewer = Viewer(ViewerOptions(sources=(RobotSource(str(PLANAR)),), port=0, rviz=document))
    viewer.start()
    started.append(viewer)
    return viewer


def _ours(tmp_path: Path) -> Path:
    """The config as robomodel writes it (its YAML layout: RViz's own)."""
    path = tmp_path / "ros2.rviz"
    path.write_text(ROS2_CONFIG)
    first = _viewer([], path)  # closed at once: only its writer is wanted
    try:
        assert first.config_panel.save(str(path))
    finally:
        first.close()
    return path


def test_every_display_of_a_file_opens_in_the_panel(started: list[Viewer], tmp_path: Path) -> None:
    path = tmp_path / "ros2.rviz"
    path.write_text(ROS2_CONFIG)
    viewer = _viewer(started, path)
    shown = [(d.class_name or "", d.name, d.enabled) for d in viewer.displays.displays]
    assert [(n, e) for _c, n, e in shown] == [("Grid", True), ("Obstacles", True), ("Depth", True), ("Plans", False), ("Imu", True)]  # fmt: skip
    grid, obstacles, depth, plans, imu = viewer.displays.displays
    assert grid.class_name == "Grid" and grid.values["Plane Cell Count"] == 10
    assert obstacles.class_name == "Marker" and plans.class_name == "MarkerArray"
    assert obstacles.values["Topic"] == "/obstacles" and obstacles.values["Queue Size"] == 7
    assert dict(plans.option("Namespaces")) == {"path": False}
    assert [r.folder.label for r in viewer.displays_panel.rows] == ["Grid", "Obstacles", "Depth", "Plans", "Imu"]  # fmt: skip
    wait_for(lambda: viewer.displays.updates > 1, what="a display update")
    for missing, class_name in ((depth, "rviz_default_plugins/DepthCloud"), (imu, "rviz_plugin_tutorials/Imu")):  # fmt: skip
        assert missing.status.level is StatusLevel.ERROR
        assert missing.status.text == (
            f"The class required for this display, '{class_name}', could not be loaded."
        )
    assert obstacles.status.text == "No messages received"
    unsupported = "rviz_default_plugins/DepthCloud, rviz_plugin_tutorials/Imu"
    assert escape_markdown(unsupported) in viewer.status_note
    assert "Marker" not in viewer.status_note.split("):")[1]


def test_a_file_saved_unchanged_is_the_same_file(started: list[Viewer], tmp_path: Path) -> None:
    path = _ours(tmp_path)
    text = path.read_text()
    assert "rviz_plugin_tutorials/Imu" in text and "Transient Local" in text
    viewer = _viewer(started, path)
    assert viewer.config_panel.save(str(path))
    assert path.read_text() == text


def test_displays_changed_added_removed_and_renamed_are_saved_and_read_back(
    started: list[Viewer], tmp_path: Path
) -> None:
    path = _ours(tmp_path)
    viewer = _viewer(started, path)
    panel = viewer.displays_panel

    def edit() -> None:
        _grid, obstacles, depth, plans, _imu = panel.rows
        obstacles.display.set_option("Topic", "/walls")
        panel.rename(plans, "Plan markers")
        plans.display.set_enabled(True)
        panel.remove(depth)
        panel.add("Marker", name="Goals", values={"Topic": "/goals", "Queue Size": 3})

    on_loop(viewer, edit)
    saved_path = tmp_path / "saved.rviz"
    assert viewer.config_panel.save(str(saved_path))
    saved = read_rviz_file(saved_path)
    assert [(d.class_name, d.name, d.enabled) for d in saved.displays] == [
        ("rviz_default_plugins/Grid", "Grid", True),
        ("rviz_default_plugins/Marker", "Obstacles", True),
        ("rviz_default_plugins/MarkerArray", "Plan markers", True),
        ("rviz_plugin_tutorials/Imu", "Imu", True),
        ("rviz_default_plugins/Marker", "Goals", True),
    ]
    topics = {d.name: d.settings.get("Topic") for d in saved.displays}
    assert topics["Obstacles"]["Value"] == "/walls" and topics["Obstacles"]["Depth"] == 7
    assert topics["Plan markers"]["Durability Policy"] == "Transient Local"  # kept as read
    assert dict(topics["Goals"]) == {
        "Value": "/goals", "Depth": 3, "Durability Policy": "Volatile",
        "History Policy": "Keep Last", "Reliability Policy": "Reliable",
    }  # fmt: skip
    again = _viewer(started, saved_path)
    assert [(d.name, dict(d.values)) for d in again.displays.displays if d.class_name] == [
        (d.name, dict(d.values)) for d in viewer.displays.displays if d.class_name
    ]


def test_ros1_files_use_rviz_1_s_keys(started: list[Viewer], tmp_path: Path) -> None:
    document, _ = open_rviz_document(str(tmp_path / "new.rviz"), RvizDialect.ROS1)
    viewer = Viewer(ViewerOptions(sources=(RobotSource(str(PLANAR)),), port=0, rviz=document))
    viewer.start()
    started.append(viewer)
    on_loop(viewer, lambda: viewer.displays_panel.add("MarkerArray", values={"Topic": "/plan"}))
    path = tmp_path / "new.rviz"
    assert viewer.config_panel.save(str(path))
    tree = yaml.safe_load(path.read_text())
    (entry,) = [d for d in tree["Visualization Manager"]["Displays"] if d["Name"] == "MarkerArray"]
    assert entry == {
        "Class": "rviz/MarkerArray", "Enabled": True, "Marker Topic": "/plan", "Name": "MarkerArray",
        "Namespaces": {}, "Queue Size": 100, "Value": True,
    }  # fmt: skip
    again = _viewer(started, path, RvizDialect.ROS1)
    grid, robot, tf, display = again.displays.displays  # the defaults, then the one added
    assert [d.class_name for d in (grid, robot, tf)] == ["Grid", "RobotModel", "TF"]
    assert grid.enabled and robot.enabled and tf.enabled
    assert display.values == viewer.displays.displays[3].values


# Saved by RViz 2: ros-controls/ros2_control_demos (Apache-2.0) at 0d9df42ab19b,
# example_4/description/rviz/rrbot.rviz, verbatim (Grid, RobotModel and a Wrench display).
EXAMPLE_4 = Path(__file__).with_name("rviz_files") / "ros2_control_demos_example_4_rrbot.rviz"


def test_a_real_config_opens_with_every_display_it_names_and_saves_unchanged(
    started: list[Viewer], tmp_path: Path
) -> None:
    from robomodel.viewer.displays.attach import MissingDisplay
    from robomodel.viewer.rviz_write import rviz_text

    viewer = _viewer(started, EXAMPLE_4)
    config = read_rviz_file(EXAMPLE_4)
    others = [d for d in config.displays if d.kind not in ("Grid", "RobotModel", "TF")]
    assert [d.class_name for d in others] == ["rviz_default_plugins/Wrench"]
    grid, robot, wrench = viewer.displays.displays
    assert grid.class_name == "Grid" and grid.config_entry == config.displays[0]
    assert (robot.class_name, robot.config_entry) == ("RobotModel", config.displays[1])
    assert wrench.name == "Wrench" and wrench.config_entry == others[0]
    wait_for(lambda: viewer.displays.updates > 1, what="a display update")
    if isinstance(wrench, MissingDisplay):  # a status line, not an error, until robomodel has it
        assert "'rviz_default_plugins/Wrench', could not be loaded" in wrench.status.text
    else:
        assert wrench.class_name == "Wrench" and wrench.topic == "/fts_broadcaster/wrench"
    saved = tmp_path / "rrbot.rviz"
    assert viewer.config_panel.save(str(saved))
    assert saved.read_text() == rviz_text(config)


# Saved by RViz 2: UniversalRobots/Universal_Robots_ROS2_Description (BSD-3-Clause) at
# 2221ec0f720fb1af99339eb891639b499b62f1da, rviz/view_robot.rviz, verbatim (Grid, RobotModel).
UR_VIEW_ROBOT = Path(__file__).with_name("rviz_files") / "ur_description_view_robot.rviz"


def test_the_ur_description_config_opens_its_grid_and_robot_model_and_saves_unchanged(
    started: list[Viewer], tmp_path: Path
) -> None:
    from robomodel.viewer.rviz_write import rviz_text

    config = read_rviz_file(UR_VIEW_ROBOT)
    assert [d.class_name for d in config.displays] == [
        "rviz_default_plugins/Grid", "rviz_default_plugins/RobotModel",
    ]  # fmt: skip
    viewer = _viewer(started, UR_VIEW_ROBOT)
    grid, robot = viewer.displays.displays  # no TF display: no frames drawn, as in RViz
    assert grid.class_name == "Grid" and grid.config_entry == config.displays[0]
    assert robot.class_name == "RobotModel" and robot.config_entry == config.displays[1]
    assert grid.values["Line Style/Line Width"] == pytest.approx(0.03)  # RViz's float32 0.03
    assert grid.values["Plane"] == "XY" and grid.values["Plane Cell Count"] == 10
    wait_for(lambda: grid.status.text == "Transform OK: base_link", what="the Grid's status")
    assert "not drawn" not in viewer.status_note
    saved = tmp_path / "view_robot.rviz"
    assert viewer.config_panel.save(str(saved))
    assert saved.read_text() == rviz_text(config) == UR_VIEW_ROBOT.read_text()


def test_open_config_replaces_the_displays_and_the_fixed_frame(
    started: list[Viewer], tmp_path: Path
) -> None:
    first = tmp_path / "first.rviz"
    first.write_text(ROS2_CONFIG)
    second = tmp_path / "second.rviz"
    second.write_text(
        ROS2_CONFIG.replace("Fixed Frame: base_link", "Fixed Frame: link_1").replace(
            "Name: Obstacles", "Name: Walls"
        )
    )
    viewer = _viewer(started, first)
    panel = viewer.config_panel
    assert not panel.open(str(tmp_path / "none.rviz"))
    assert "**Not opened**" in panel.status.content and "does not exist" in panel.status.content
    assert panel.open(str(second))
    wait_for(
        lambda: (
            [d.name for d in viewer.displays.displays] == ["Grid", "Walls", "Depth", "Plans", "Imu"]
        ),
        what="the second file's displays",
    )
    assert viewer.fixed_frame == "link_1" and viewer.fixed_dropdown.value == "link_1"
    # the panel's rows follow the displays on the loop thread
    wait_for(lambda: [r.folder.label for r in viewer.displays_panel.rows] == ["Grid", "Walls", "Depth", "Plans", "Imu"],
             what="the panel's rows")  # fmt: skip
    assert panel.document.path == str(second)
    assert panel.save(str(second))  # Save Config now writes the file opened
    assert read_rviz_file(second).fixed_frame == "link_1"
