"""RobotModel and TF are displays like the others: RViz's options and defaults, read
from and written to ROS 1 and ROS 2 configs, added, removed, enabled and set in a viewer; a
config without a RobotModel shows no robot, as RViz; without a config every robot has one."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path
from types import MappingProxyType, SimpleNamespace
from typing import Any

import numpy as np
import pytest
import yaml

from robomodel.viewer import RobotSource, Viewer, ViewerOptions
from robomodel.viewer.displays import display_class
from robomodel.viewer.displays.robot_model import LinkUpdates, show_robots
from robomodel.viewer.displays.rviz_io import display_entry, display_values
from robomodel.viewer.rviz_document import default_rviz_config, open_rviz_document
from robomodel.viewer.rviz_model import RvizDialect
from tests.conftest import EXAMPLES
from tests.viewer.conftest import wait_for
from tests.viewer.fake_scene import FakeScene, fake_context
from tests.viewer.test_tools_inprocess import on_loop

PLANAR = EXAMPLES / "gripper_description/urdf/planar_3dof.urdf"
RobotModel, TF = display_class("rviz/RobotModel"), display_class("rviz_default_plugins/TF")


def _entry(dialect: RvizDialect, kind: str) -> Any:
    config = default_rviz_config(dialect)
    return config.displays[config.last(kind) or 0]


@pytest.mark.parametrize("dialect", list(RvizDialect))
def test_rviz_s_own_robot_model_and_tf_entries_read_as_the_defaults(dialect: RvizDialect) -> None:
    """RViz's defaults (as RViz 1 and RViz 2 save them) are the displays' own defaults, and a
    display written unchanged is the entry it was read from."""
    context = fake_context(FakeScene())
    for cls in (RobotModel, TF):
        entry = _entry(dialect, cls.class_name)
        values, skipped = display_values(cls, entry.settings, dialect)
        assert skipped == []
        display = cls(entry.name, context, values)
        defaults = cls(entry.name, context)
        changed = {k: v for k, v in display.values.items() if defaults.values[k] != v}
        # RViz 1 names the parameter, relative; RViz 2 the topic
        expected = {"Description Topic": "robot_description"} if cls is RobotModel and dialect is RvizDialect.ROS1 else {}  # fmt: skip
        assert changed == expected
        assert display_entry(display, dialect, entry) == entry


def test_a_new_robot_model_is_written_in_each_rviz_s_form() -> None:
    display = RobotModel("Robot", fake_context(FakeScene()), {"Alpha": 0.5, "TF Prefix": "r1"})
    ros1 = dict(display_entry(display, RvizDialect.ROS1).settings)
    assert display_entry(display, RvizDialect.ROS1).class_name == "rviz/RobotModel"
    assert ros1 == {"Alpha": 0.5, "Collision Enabled": False, "Robot Description": "/robot_description",
                    "TF Prefix": "r1", "Update Interval": 0.0, "Visual Enabled": True}  # fmt: skip
    ros2 = display_entry(display, RvizDialect.ROS2)
    assert ros2.class_name == "rviz_default_plugins/RobotModel"
    assert ros2.settings["Description Source"] == "Topic"
    assert ros2.settings["Description Topic"]["Value"] == "/robot_description"
    assert "Robot Description" not in ros2.settings
    back, skipped = display_values(RobotModel, ros2.settings, RvizDialect.ROS2)
    assert skipped == [] and back == display.values


def test_tf_frames_are_read_switched_and_written_as_rviz_does() -> None:
    settings = MappingProxyType({"Frames": {"All Enabled": True, "odom": {"Value": False}},
                                 "Marker Scale": 0.5, "Show Names": True})  # fmt: skip
    values, _ = display_values(TF, settings, RvizDialect.ROS1)
    scene = FakeScene()
    tf = TF("TF", fake_context(scene, clock=lambda: 10**12), values)
    buffer = _Buffer({"base_link": (None, None), "odom": (None, "base_link"),
                      "laser": (10**12, "base_link")})  # fmt: skip
    frames = ("base_link", "odom", "laser")
    xyz = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0]])
    tf.show_frames(frames, np.tile([1.0, 0, 0, 0], (3, 1)), xyz, np.ones(3, bool), buffer)
    assert tf.shown == ("base_link", "laser")  # odom switched off in the file
    axes = scene.nodes["/displays/TF/axes/x"]
    np.testing.assert_allclose(axes.kwargs["batched_positions"], [[0, 0, 0], [0, 1, 0]])
    assert axes.kwargs["args"][0][:, 0].max() == pytest.approx(0.05)  # 0.1 m at Marker Scale 0.5
    arrows = scene.nodes["/displays/TF/arrows"].kwargs
    np.testing.assert_allclose(arrows["points"], [[[0, 1, 0], [0, 0, 0]]])  # laser -> parent
    assert arrows["colors"].tolist() == [[[204, 204, 77], [255, 26, 153]]]  # shaft, head
    assert {"base_link", "laser"} <= set(tf.map_entries("Frames"))  # listed, as RViz lists them
    assert set(tf.option("Frames")) == {"All Enabled", "odom"}
    written = display_entry(tf, RvizDialect.ROS1, _entry_of(settings)).settings
    assert written == settings  # frames only seen are not saved
    tf.set_option("Frames", {**tf.option("Frames"), "laser": {"Value": False}})
    assert dict(display_entry(tf, RvizDialect.ROS1).settings["Frames"]) == {
        "All Enabled": True, "odom": {"Value": False}, "laser": {"Value": False}}  # fmt: skip
    tf.set_option("Frames", {**tf.option("Frames"), "All Enabled": False})  # all follow it
    assert not any(v["Value"] for k, v in tf.map_entries("Frames").items() if k != "All Enabled")


def test_a_frame_older_than_the_frame_timeout_is_not_drawn_and_static_ones_never_age() -> None:
    now = [100 * 10**9]
    scene = FakeScene()
    tf = TF("TF", fake_context(scene, clock=lambda: now[0]), {"Frame Timeout": 5.0})
    buffer = _Buffer({"map": (None, None), "static": (None, "map"), "moving": (99 * 10**9, "map")})
    frames = ("map", "static", "moving")
    args = (np.tile([1.0, 0, 0, 0], (3, 1)), np.zeros((3, 3)), np.ones(3, bool), buffer)
    tf.show_frames(frames, *args)
    assert tf.shown == frames
    now[0] += 10 * 10**9
    tf.show_frames(frames, *args)
    assert tf.shown == ("map", "static")
    tf.set_option("Update Interval", 60.0)
    tf.show_frames(("map",), args[0][:1], args[1][:1], args[2][:1], buffer)
    now[0] += 10**9
    tf.show_frames(frames, *args)  # within the interval: not updated
    assert tf.shown == ("map",)
    tf.set_enabled(False)
    assert scene.nodes == {}
    tf.set_enabled(True)
    now[0] += 61 * 10**9
    tf.show_frames(frames, *args)
    assert scene.nodes and tf.shown == ("map", "static")
    tf.close()  # removed from the panel
    assert scene.nodes == {}


class _Buffer:
    def __init__(self, parents: dict[str, tuple[int | None, str | None]]) -> None:
        self.parents = parents

    def latest_parent(self, frame: str) -> tuple[int | None, str | None]:
        return self.parents.get(frame, (None, None))

    def latest_common_time_ns(self, _fixed: str, frame: str | None) -> int:
        stamps = []  # the newest stamps up to the root (the fixed frame's, in these tests)
        while frame is not None:
            stamp, frame = self.latest_parent(frame)
            stamps.append(stamp or 0)
        return min((s for s in stamps if s), default=0)


def _entry_of(settings: Any) -> Any:
    from robomodel.viewer.rviz_model import RvizDisplay

    return RvizDisplay("rviz/TF", "TF", True, settings)


class _Drawing:
    def __init__(self) -> None:
        self.shown, self.alpha, self.show_visual, self.show_collision = True, 1.0, True, False

    def set_shown(self, shown: bool) -> None:
        self.shown = shown

    def set_alpha(self, alpha: float) -> None:
        self.alpha = alpha

    def set_visual_enabled(self, on: bool) -> None:
        self.show_visual = on

    def set_collision_enabled(self, on: bool) -> None:
        self.show_collision = on


def _robot(topic: str, path: str = "/nowhere.urdf") -> Any:
    return SimpleNamespace(description_topic=topic, description_names=(topic,), source=SimpleNamespace(path=path),
                           display=_Drawing(), prefix="", label=topic, failure=None,
                           robot=object(), last_poses=None, link_updates=LinkUpdates())  # fmt: skip


def test_each_robot_is_drawn_as_the_last_enabled_robot_model_naming_it_says(tmp_path: Path) -> None:
    one, two = _robot("/robot_description"), _robot("/r2/robot_description", str(PLANAR))
    context = fake_context(FakeScene())
    context.robots = lambda: (one, two)
    first = RobotModel("A", context, {"Alpha": 0.5})
    second = RobotModel("B", context, {"Description Topic": "robot_description",
                                       "Collision Enabled": True})  # fmt: skip
    show_robots([first, second], [one, two])
    assert (one.display.shown, two.display.shown) == (True, False)  # none names /r2
    assert (one.display.alpha, one.display.show_collision) == (1.0, True)  # B's, the last
    assert "the viewer's robots are described on /r2/robot_description, /robot_description" in (
        RobotModel("C", context, {"Description Topic": "/x"}).draw(lambda f, s: None).text
    )  # fmt: skip
    second.set_enabled(False)
    show_robots([first, second], [one, two])
    assert (one.display.alpha, one.display.show_collision) == (0.5, False)  # A's now
    by_file = RobotModel("F", context, {"Description Source": "File",
                                        "Description File": str(PLANAR)})  # fmt: skip
    show_robots([by_file], [one, two])
    assert (one.display.shown, two.display.shown) == (False, True)
    assert by_file.draw(lambda f, s: None).text == "Showing /r2/robot_description"


@pytest.fixture
def started() -> Iterator[list[Viewer]]:
    viewers: list[Viewer] = []
    yield viewers
    for viewer in viewers:
        viewer.close()


GRID_ONLY = """Visualization Manager:
  Class: ""
  Displays:
    - Class: rviz_default_plugins/Grid
      Enabled: true
      Name: Grid
  Global Options:
    Fixed Frame: base_link
"""


def test_a_config_without_robot_model_shows_no_robot_until_one_is_added(
    started: list[Viewer], tmp_path: Path
) -> None:
    path = tmp_path / "grid.rviz"
    path.write_text(GRID_ONLY)
    document, _ = open_rviz_document(str(path), RvizDialect.ROS2)
    viewer = Viewer(ViewerOptions(sources=(RobotSource(str(PLANAR)),), port=0, rviz=document))
    viewer.start()
    started.append(viewer)
    drawing = viewer.sessions[0].display
    assert [d.class_name for d in viewer.displays.displays] == ["Grid"]
    assert not drawing.shown  # RViz draws no robot without a RobotModel display
    panel = viewer.displays_panel
    robot = on_loop(viewer, lambda: panel.add("RobotModel"))
    wait_for(lambda: drawing.shown, what="the robot drawn")
    on_loop(viewer, lambda: robot.set_option("Alpha", 0.3))
    wait_for(lambda: drawing.alpha == 0.3, what="its Alpha")
    on_loop(viewer, lambda: robot.set_enabled(False))
    wait_for(lambda: not drawing.shown, what="the robot hidden")
    on_loop(viewer, lambda: panel.remove(panel.rows[-1]))
    assert [d.class_name for d in viewer.displays.displays] == ["Grid"]
    saved = tmp_path / "saved.rviz"
    tf = on_loop(viewer, lambda: panel.add("TF"))
    on_loop(viewer, lambda: viewer.displays.rename(tf, "Frames"))
    wait_for(lambda: tf.shown, what="the TF display's frames")
    assert {"base_link", "link_1"} <= set(tf.shown)
    assert viewer.config_panel.save(str(saved))
    tree = yaml.safe_load(saved.read_text())["Visualization Manager"]["Displays"]
    assert [(d["Class"], d["Name"]) for d in tree] == [
        ("rviz_default_plugins/Grid", "Grid"), ("rviz_default_plugins/TF", "Frames")]  # fmt: skip


def test_without_a_config_each_robot_has_its_robot_model(started: list[Viewer]) -> None:
    """seed 004's two robots: one RobotModel display each, on its namespace's topic and with
    its frame prefix as TF Prefix (so that RViz shows the saved config the same)."""
    xacro = str(EXAMPLES / "example_description/urdf/example.urdf.xacro")
    sources = (RobotSource(xacro, prefix="robot1/"), RobotSource(xacro, prefix="robot2/"))
    viewer = Viewer(ViewerOptions(sources=sources, port=0))
    viewer.start()
    started.append(viewer)
    models = [d for d in viewer.displays.displays if d.class_name == "RobotModel"]
    assert [(d.name, d.option("Description Topic"), d.option("TF Prefix")) for d in models] == [
        ("RobotModel", "/robot1/robot_description", "robot1"),
        ("RobotModel (2)", "/robot2/robot_description", "robot2"),
    ]
    assert all(s.display.shown for s in viewer.sessions)
    wait_for(lambda: models[1].status.text.startswith("Showing robot2/"), what="its status")
    on_loop(viewer, lambda: models[1].set_option("Visual Enabled", False))
    wait_for(lambda: not viewer.sessions[1].display.show_visual, what="robot2's visuals hidden")
    assert viewer.sessions[0].display.show_visual


def test_a_ros_1_launch_s_robot_answers_to_the_parameter_it_was_read_from() -> None:
    """A robot_state_publisher in /r1 that read /robot_description (roscpp's searchParam):
    RViz 1's RobotModel with Robot Description ``robot_description`` draws it, and so does one
    naming the namespace's topic; another parameter does not."""
    from robomodel.description.packages import PackageIndex
    from robomodel.viewer.session import RobotSession

    source = RobotSource(str(PLANAR), namespace="/r1", description_name="robot_description")
    session = RobotSession(0, source, index=PackageIndex(), namespace="/r1")
    assert session.description_names == ("/r1/robot_description", "/robot_description")
    context = fake_context(FakeScene())
    for name, drawn in (("robot_description", True), ("/r1/robot_description", True),
                        ("other_description", False)):  # fmt: skip
        assert RobotModel("R", context, {"Description Topic": name}).describes(session) is drawn
