"""RViz configs read, written in RViz's own format, and read back unchanged.

RViz's own default config (Debian's /usr/share/rviz/default.rviz) is rewritten byte for byte;
every .rviz robomodel ships reads back equal after a write; arbitrary trees survive the
writer; a -d file that does not exist is RViz's defaults with RobotModel and TF; saving what
the viewer shows changes only what differs from what the file implies.
"""

from __future__ import annotations

import math
import os
from dataclasses import replace
from pathlib import Path
from typing import Any

import pytest
import yaml
from hypothesis import example, given, settings
from hypothesis import strategies as st

from robomodel.viewer.displays import display_class
from robomodel.viewer.displays.attach import config_with_displays
from robomodel.viewer.displays.rviz_io import display_values
from robomodel.viewer.rviz_config import RvizConfigError, parse_rviz_text, read_rviz_file
from robomodel.viewer.rviz_document import default_rviz_config, open_rviz_document
from robomodel.viewer.rviz_model import RvizDialect
from robomodel.viewer.rviz_state import (
    OrbitCamera,
    ViewerState,
    config_with_state,
    implied_state,
)
from robomodel.viewer.rviz_write import RvizSaveError, rviz_text, write_rviz_config
from robomodel.viewer.rviz_yaml import dump_rviz_yaml
from tests.conftest import EXAMPLES
from tests.viewer.fake_scene import FakeScene, fake_context

DEBIAN_DEFAULT = Path("/usr/share/rviz/default.rviz")
ROOT = Path(__file__).resolve().parents[2]
SHIPPED = sorted(
    [*EXAMPLES.rglob("*.rviz"), *(ROOT / "tests").rglob("*.rviz"),
     *(ROOT / "src/robomodel/viewer/rviz_defaults").glob("*.rviz")]
)  # fmt: skip


# Saved by RViz 2: ros-controls/ros2_control_demos (Apache-2.0) at 0d9df42ab19b,
# ros2_control_demo_description/r6bot/rviz/view_robot.rviz, verbatim.
RVIZ2_SAVED = Path(__file__).with_name("rviz_files") / "r6bot_view_robot.rviz"


@pytest.mark.parametrize("path", [DEBIAN_DEFAULT, RVIZ2_SAVED], ids=["rviz1", "rviz2"])
def test_files_rviz_wrote_are_rewritten_byte_for_byte(path: Path) -> None:
    """The writer's layout is RViz's: key order, indentation, quoting, ``{}``, ``~``
    (RViz 1's default config; an RViz 2 file with RobotModel, TF and per-link settings)."""
    if not path.exists():
        pytest.fail(f"{path} is missing: tools/system-deps test installs Debian's rviz")
    text = path.read_text()
    assert rviz_text(parse_rviz_text(text, str(path))) == text


@pytest.mark.parametrize("path", SHIPPED, ids=lambda p: p.name)
def test_read_write_read_is_the_identity(path: Path) -> None:
    config = read_rviz_file(path)
    text = rviz_text(config)
    again = parse_rviz_text(text, "written")
    assert again == config
    assert rviz_text(again) == text


_scalars = (
    st.none()
    | st.booleans()
    | st.integers(-(2**40), 2**40)
    | st.floats(allow_nan=False, allow_infinity=False)
    | st.text(st.characters(exclude_categories=("Cs",)), max_size=12)
)
_keys = st.text(st.characters(exclude_categories=("Cs",)), min_size=0, max_size=10)
_trees = st.recursive(
    _scalars,
    lambda inner: st.lists(inner, max_size=4) | st.dictionaries(_keys, inner, max_size=4),
    max_leaves=20,
)


@settings(max_examples=300, deadline=None)
@given(st.dictionaries(_keys, _trees, max_size=5))
def test_every_tree_reads_back_as_written(tree: dict[str, Any]) -> None:
    text = dump_rviz_yaml(tree)
    assert yaml.safe_load(text) == (tree or {})


_names = st.text(st.characters(exclude_categories=("Cs",)), min_size=1, max_size=8)


@settings(max_examples=150, deadline=None)
@given(
    fixed=st.none() | _names,
    rate=st.none() | st.floats(1, 1000),
    kinds=st.lists(st.sampled_from(["Grid", "RobotModel", "TF", "LaserScan"]), max_size=4),
    values=st.dictionaries(_names, _trees, max_size=3),
    enabled=st.booleans(),
    dialect=st.sampled_from(list(RvizDialect)),
)
@example(None, None, ["Grid"], {"Class": None}, False, RvizDialect.ROS1)
@example(None, None, ["TF"], {"Value": "x"}, True, RvizDialect.ROS2)
def test_generated_configs_round_trip(
    fixed: str | None,
    rate: float | None,
    kinds: list[str],
    values: dict[str, Any],
    enabled: bool,
    dialect: RvizDialect,
) -> None:
    displays = [
        {**values, "Class": dialect.display_class(k), "Name": k, "Enabled": enabled} for k in kinds
    ]
    tree = {
        "Panels": [],
        "Visualization Manager": {
            "Class": "",
            "Displays": displays,
            "Global Options": {"Fixed Frame": fixed, "Frame Rate": rate},
        },
    }
    config = parse_rviz_text(dump_rviz_yaml(tree), "generated")
    assert [d.kind for d in config.displays] == kinds
    assert all(d.enabled is enabled for d in config.displays)
    again = parse_rviz_text(rviz_text(config), "written")
    assert again == config
    assert rviz_text(again) == rviz_text(config)


@pytest.mark.parametrize(
    ("dialect", "prefix"),
    [(RvizDialect.ROS1, "rviz/"), (RvizDialect.ROS2, "rviz_default_plugins/")],
)
def test_a_missing_file_is_rviz_s_defaults_with_robot_model_and_tf(
    tmp_path: Path, dialect: RvizDialect, prefix: str
) -> None:
    path = tmp_path / "urdf" / "urdf.rviz"
    document, warning = open_rviz_document(str(path), dialect)
    assert warning is not None and str(path) in warning and "\n" not in warning
    assert document.missing and document.path == str(path) and document.dialect is dialect
    config = document.config
    assert [d.class_name for d in config.displays] == [
        prefix + k for k in ("Grid", "RobotModel", "TF")
    ]
    assert all(d.enabled for d in config.displays)
    assert config.fixed_frame is None  # the viewer's (the root link) is saved
    assert config.view is not None and config.view.class_name == prefix + "Orbit"
    assert "Window Geometry" in config.other and "Panels" in config.other
    if dialect is RvizDialect.ROS2:
        robot = config.displays[1].settings
        assert robot["Description Source"] == "Topic"
        assert robot["Description Topic"]["Value"] == "/robot_description"
    assert not path.exists()  # nothing is written until Save Config


def test_a_file_that_exists_but_is_not_an_rviz_config_stays_an_error(tmp_path: Path) -> None:
    bad = tmp_path / "bad.rviz"
    bad.write_text("Visualization Manager: [1, 2\n")
    with pytest.raises(RvizConfigError) as error:
        open_rviz_document(str(bad), RvizDialect.ROS1)
    assert f"{bad}:" in str(error.value) and not error.value.missing
    bad.write_text("Panels: []\n")
    with pytest.raises(RvizConfigError, match="no 'Visualization Manager'"):
        open_rviz_document(str(bad), RvizDialect.ROS1)


def _state(document: Any, **changes: Any) -> ViewerState:
    return replace(implied_state(document), **changes)


def _displays(document: Any) -> list[Any]:
    """The document's displays as the Displays panel opens them (RobotModel and TF too)."""
    out = []
    for entry in document.config.displays:
        cls = display_class(entry.class_name)
        values, _ = display_values(cls, entry.settings, document.dialect)
        display = cls(entry.name, fake_context(FakeScene()), values, enabled=entry.enabled)
        display.config_entry = entry
        out.append(display)
    return out


def _saved(document: Any, displays: list[Any], state: ViewerState | None = None) -> Any:
    config = config_with_state(document, state or implied_state(document))
    return config_with_displays(displays, config, document.dialect)[0]


def test_saving_the_implied_state_changes_nothing() -> None:
    document, _ = open_rviz_document(
        str(EXAMPLES / "gripper_description/urdf/urdf.rviz"), RvizDialect.ROS1
    )
    state = implied_state(document)
    assert state.fixed_frame == "base_link"
    assert state.camera is not None and state.camera.distance_m == 2.5
    displays = _displays(document)
    tf = next(d for d in displays if d.class_name == "TF")
    assert tf.option("Marker Scale") == 0.5
    assert _saved(document, displays, state) == document.config


def test_saving_a_changed_state_writes_what_the_viewer_shows() -> None:
    document, _ = open_rviz_document(
        str(EXAMPLES / "gripper_description/urdf/urdf.rviz"), RvizDialect.ROS1
    )
    camera = OrbitCamera((0.1, 0.2, 0.3), 3.0, 1.0, 0.5)
    state = _state(document, fixed_frame="link_1", frame_rate_hz=20.0, camera=camera)
    displays = _displays(document)
    by_kind = {d.class_name: d for d in displays}
    by_kind["TF"].set_enabled(False)
    by_kind["RobotModel"].set_option("Collision Enabled", True)
    by_kind["RobotModel"].set_option("Alpha", 0.4)
    config = _saved(document, displays, state)
    assert config.fixed_frame == "link_1" and config.frame_rate_hz == 20.0
    saved = {d.kind: d for d in config.displays}
    assert not saved["TF"].enabled and saved["TF"].settings["Show Axes"] is True  # kept
    robot = saved["RobotModel"].settings
    assert robot["Collision Enabled"] is True and robot["Alpha"] == 0.4
    assert robot["Robot Description"] == "robot_description"  # RViz 1's key, kept
    assert config.view is not None and config.view.settings["Distance"] == 3.0
    assert config.view.settings["Focal Point"] == {"X": 0.1, "Y": 0.2, "Z": 0.3}
    assert config.displays[0].settings["Cell Size"] == 1  # what the viewer has not, kept
    reread = replace(document, config=parse_rviz_text(rviz_text(config), "saved"))
    assert implied_state(reread) == state
    again = {d.class_name: d for d in _displays(reread)}
    assert again["RobotModel"].values == by_kind["RobotModel"].values
    assert not again["TF"].enabled


def test_a_display_the_file_lacks_is_added_in_the_file_s_dialect() -> None:
    text = (
        'Visualization Manager:\n  Class: ""\n  Displays:\n'
        "    - Class: rviz_default_plugins/Grid\n      Enabled: true\n      Name: Grid\n"
    )
    document = replace(
        default_document := open_rviz_document(None, RvizDialect.ROS2)[0],
        config=parse_rviz_text(text, "grid-only"),
    )
    assert default_document.dialect is RvizDialect.ROS2
    displays = _displays(document)
    assert [d.class_name for d in displays] == ["Grid"]  # no robot, no frames: as RViz
    context = fake_context(FakeScene())
    displays += [display_class("RobotModel")("RobotModel", context), display_class("TF")("TF", context)]  # fmt: skip
    config = _saved(document, displays)
    classes = [d.class_name for d in config.displays]
    assert classes == [f"rviz_default_plugins/{k}" for k in ("Grid", "RobotModel", "TF")]
    robot, tf = config.displays[1].settings, config.displays[2].settings
    assert robot["Description Topic"]["Value"] == "/robot_description"
    assert robot["Description Source"] == "Topic" and robot["Visual Enabled"] is True
    assert tf["Frames"] == {"All Enabled": True} and tf["Frame Timeout"] == 15.0


def test_the_orbit_camera_is_rviz_s() -> None:
    """rviz::OrbitViewController::updateCamera, and back (calculatePitchYawFromPosition)."""
    camera = OrbitCamera((0.5, -0.25, 0.1), 2.5, 5.5, 0.33)
    x, y, z = camera.position_m()
    assert z == pytest.approx(0.1 + 2.5 * math.sin(0.33))
    assert x == pytest.approx(0.5 + 2.5 * math.cos(5.5) * math.cos(0.33))
    back = OrbitCamera.looking((x, y, z), camera.focal_point_m)
    assert back.close_to(camera) and back.yaw_rad == pytest.approx(5.5, abs=1e-5)


def test_writing_is_atomic_and_a_bad_path_is_a_clear_error(tmp_path: Path) -> None:
    config = default_rviz_config(RvizDialect.ROS1)
    target = write_rviz_config(tmp_path / "new" / "config" / "view_urdf.rviz", config)
    assert read_rviz_file(target) == config
    os.chmod(target, 0o600)
    write_rviz_config(target, replace(config, fixed_frame="odom"))
    assert read_rviz_file(target).fixed_frame == "odom"
    assert target.stat().st_mode & 0o777 == 0o600  # the file's own mode is kept
    assert sorted(p.name for p in target.parent.iterdir()) == ["view_urdf.rviz"]
    with pytest.raises(RvizSaveError, match="it is a directory"):
        write_rviz_config(tmp_path, config)
    blocked = tmp_path / "file"
    blocked.write_text("x")
    with pytest.raises(RvizSaveError, match=f"cannot save RViz config to {blocked}/a.rviz"):
        write_rviz_config(blocked / "a.rviz", config)


def test_without_d_the_view_and_background_stay_robomodel_s() -> None:
    document, warning = open_rviz_document(None, RvizDialect.ROS2)
    assert warning is None and document.path is None and document.missing
    assert implied_state(document).camera is None


def test_the_frame_rate_is_saved_only_when_changed() -> None:
    document, _ = open_rviz_document(None, RvizDialect.ROS1)
    state = implied_state(document, frame_rate_hz=60.0)
    assert config_with_state(document, state, frame_rate_hz=60.0).frame_rate_hz is None
    changed = config_with_state(document, replace(state, frame_rate_hz=30.0), frame_rate_hz=60.0)
    assert changed.frame_rate_hz == 30.0


def test_a_setting_that_is_not_a_number_keeps_the_default() -> None:
    text = (
        "Visualization Manager:\n  Displays:\n"
        "    - Class: rviz/RobotModel\n      Alpha: half\n      Name: RobotModel\n"
    )
    document = replace(
        open_rviz_document(None, RvizDialect.ROS1)[0], config=parse_rviz_text(text, "x")
    )
    entry = document.config.displays[0]
    values, skipped = display_values(display_class("RobotModel"), entry.settings, RvizDialect.ROS1)
    assert "Alpha" not in values and "half" in skipped[0]  # the display keeps 1.0
    (robot,) = _displays(document)
    assert robot.option("Alpha") == 1.0
    assert rviz_text(_saved(document, [robot])).count("Alpha: half") == 1  # kept as written


def test_yaml_scalars_as_rviz_writes_them() -> None:
    from robomodel.viewer.rviz_yaml import dump_rviz_yaml

    text = dump_rviz_yaml(
        {"Small": 1e-05, "Big": -math.inf, "Spaced": "a b ", "Break": "a\u2028b",
         "Astral": "a\U0001f916\u0085", "Nested": [[], {}, [1]]}
    )  # fmt: skip
    assert 'Astral: "a\U0001f916\\x85"' in text
    assert "Small: 1.0e-05" in text and 'Spaced: "a b "' in text
    assert 'Break: "a\\u2028b"' in text and "Big: -.inf" in text
    assert "  - []\n  - {}\n" in text
    assert yaml.safe_load(text) == {
        "Small": 1e-05, "Big": -math.inf, "Spaced": "a b ", "Break": "a\u2028b",
        "Astral": "a\U0001f916\u0085", "Nested": [[], {}, [1]],
    }  # fmt: skip


def test_config_details_rviz_reads() -> None:
    text = """Visualization Manager:
  Class: ""
  Displays:
    - Class: rviz_default_plugins/Grid
      Enabled: true
    - Class: rviz_default_plugins/RobotModel
      Name: Robot
      Description Topic:
        Value: /my_robot_description
  Global Options:
    Background Color: 10,20,30
    Fixed Frame: base_link
"""
    config = parse_rviz_text(text, "v.rviz")
    assert [d.name for d in config.displays] == ["Grid", "Robot"]  # a missing Name: the class's
    assert config.background_rgb == (10, 20, 30)  # RViz 2 separates by ";", old files by ","
    from robomodel.viewer.rviz_config import settings_of

    assert settings_of(config).robot_description == "my_robot_description"
    ros1 = text.replace("Description Topic:\n        Value: /my_robot_description",
                        "Robot Description: arm_description")  # fmt: skip
    assert settings_of(parse_rviz_text(ros1, "v.rviz")).robot_description == "arm_description"
    changed = config.displays[1].with_settings({"Alpha": 0.5}, enabled=False)
    assert (changed.class_name, changed.name, changed.enabled) == (
        "rviz_default_plugins/RobotModel", "Robot", False,
    )  # fmt: skip
    assert changed.settings["Alpha"] == 0.5 and "Description Topic" in changed.settings
    assert config.displays[1].with_settings({}).enabled is True


def test_invalid_yaml_is_named_with_its_line_and_column() -> None:
    with pytest.raises(RvizConfigError) as refused:
        parse_rviz_text("Visualization Manager:\n  Displays: [\n", "bad.rviz")
    message = str(refused.value)
    assert message.startswith("bad.rviz:3:1: invalid RViz config: ")
    assert "\n" not in message
    with pytest.raises(RvizConfigError) as deep:
        parse_rviz_text("a: " + "[" * 300 + "]" * 300 + "\n", "deep.rviz")
    assert (
        str(deep.value) == "deep.rviz:1:103: invalid RViz config: nested more than 100 levels deep"
    )
