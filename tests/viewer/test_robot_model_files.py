"""A RobotModel display with Description Source File naming a file the viewer did not load
loads that robot, as RViz 2's does (robot_model_display.cpp, ``load_urdf_from_file``): drawn
from TF, publishing nothing; robomodel also reads xacro, reloads the file when it changes and
shows the loader's file:line for an error. The robot goes with its display."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from robomodel.runtime.msg import TFMessage
from robomodel.runtime.qos import latched
from robomodel.viewer import RobotSource, Viewer, ViewerOptions
from robomodel.viewer.displays.base import Display, StatusLevel
from robomodel.viewer.session import RobotSession
from tests.viewer.conftest import wait_for
from tests.viewer.planar_viewer import PLANAR, planar_viewer  # noqa: F401  (the fixture)
from tests.viewer.test_robot_model_topics import MAST, _link_xyz, _static
from tests.viewer.test_tools_inprocess import on_loop

FLAG = """  <link name="mast_flag"><visual><geometry><box size="0.1 0.3 0.1"/></geometry></visual></link>
  <joint name="hoist" type="fixed">
    <parent link="mast_top"/><child link="mast_flag"/><origin xyz="0 0 0.5"/>
  </joint>
</robot>"""
MAST_XACRO = """<robot name="mast" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="height" value="1"/>
  <link name="mast_base"><visual><geometry><box size="0.2 0.2 ${height}"/></geometry></visual></link>
</robot>
"""


def _publish_mast_tf(viewer: Viewer) -> None:
    """The mast's links in TF (/tf_static, latched), beside the arm: 2 m along y, its top 1 m
    up, a flag 0.5 m above that (a link the file gains later)."""
    assert viewer.context is not None
    node = on_loop(viewer, lambda: viewer.context.create_node("mast_tf"))  # type: ignore[union-attr]
    statics = on_loop(viewer, lambda: node.create_publisher(TFMessage, "/tf_static", latched(10)))
    tree = TFMessage([_static("base_link", "mast_base", (0.0, 2.0, 0.0)),
                      _static("mast_base", "mast_top", (0.0, 0.0, 1.0)),
                      _static("mast_top", "mast_flag", (0.0, 0.0, 0.5))])  # fmt: skip
    on_loop(viewer, lambda: statics.publish(tree))


def _mast(viewer: Viewer) -> RobotSession | None:
    return next((s for s in viewer.sessions if s.robot is not None and s.robot.name == "mast"), None)  # fmt: skip


def _add_file_model(viewer: Viewer, path: Path | str) -> Display:
    panel = viewer.displays_panel
    values = {"Description Source": "File", "Description File": str(path)}
    return on_loop(viewer, lambda: panel.add("RobotModel", name="Mast", values=values))  # type: ignore[no-any-return]


def test_a_robot_model_naming_another_file_loads_draws_and_drops_that_robot(
    viewer: Viewer, tmp_path: Path
) -> None:
    path = tmp_path / "mast.urdf"
    path.write_text(MAST)
    _publish_mast_tf(viewer)
    own = viewer.sessions[0]
    model = _add_file_model(viewer, path)
    wait_for(lambda: (p := _link_xyz(viewer, "mast", "mast_top")) is not None and np.allclose(p, (0, 2, 1)),
             what="the mast's top drawn from TF at (0, 2, 1)")  # fmt: skip
    wait_for(lambda: model.status.text == "Showing mast", what="its status")
    mast = _mast(viewer)
    assert mast is not None and mast.display is not None and mast.display.shown
    assert mast.source.path == str(path) and mast.source.topic is None
    assert mast.rsp is None and mast.jsp is None  # RViz publishes nothing for its robot
    assert own.robot is not None and own.robot.name == "planar_3dof"
    root = mast.display.root
    assert root in viewer.server.scene._handle_from_node_name  # viser 1.1's table of nodes

    on_loop(viewer, lambda: model.set_enabled(False))  # RViz's onDisable: clear()
    wait_for(lambda: _mast(viewer) is None, what="the mast dropped while disabled")
    assert root not in viewer.server.scene._handle_from_node_name
    on_loop(viewer, lambda: model.set_enabled(True))  # onEnable: load_urdf() reads it again
    wait_for(lambda: model.status.text == "Showing mast", what="the mast back")

    mast = _mast(viewer)
    on_loop(viewer, lambda: model.set_option("Description File", str(PLANAR)))  # pointed elsewhere
    wait_for(lambda: _mast(viewer) is None, what="the mast dropped with its file")
    wait_for(lambda: model.status.text == "Showing planar_3dof", what="the viewer's own robot")
    assert viewer.sessions == [own]  # the viewer's file: no second session for it
    on_loop(viewer, lambda: model.set_option("Description File", str(path)))
    wait_for(lambda: model.status.text == "Showing mast", what="the mast once more")
    on_loop(viewer, lambda: model.set_option("Description Source", "Topic"))
    wait_for(lambda: _mast(viewer) is None, what="the mast dropped for the topic")

    on_loop(viewer, lambda: model.set_option("Description Source", "File"))
    wait_for(lambda: _mast(viewer) is not None, what="the mast for the file again")
    panel = viewer.displays_panel
    on_loop(viewer, lambda: panel.remove(panel.rows[-1]))  # the display removed: the robot goes
    wait_for(lambda: viewer.sessions == [own], what="the mast dropped with its display")


def test_the_file_edited_brings_its_new_link(viewer: Viewer, tmp_path: Path) -> None:
    """The viewer's FileWatcher reloads the display's file when it changes: a link added to
    it is drawn where TF has it (RViz 2 reads the file only when enabled or renamed)."""
    path = tmp_path / "mast.urdf"
    path.write_text(MAST)
    _publish_mast_tf(viewer)
    model = _add_file_model(viewer, path)
    wait_for(lambda: model.status.text == "Showing mast", what="the mast")
    mast = _mast(viewer)
    assert mast is not None and mast.robot is not None
    assert "mast_flag" not in mast.robot.link_names
    reloads = viewer.reloads
    path.write_text(MAST.replace("</robot>", FLAG))
    # the session's model is replaced before its drawing is: wait for the drawing's link
    wait_for(lambda: (d := mast.display) is not None and "mast_flag" in d.link_names
             and (p := _link_xyz(viewer, "mast", "mast_flag")) is not None and np.allclose(p, (0, 2, 1.5)),
             what="the new flag drawn from TF at (0, 2, 1.5)")  # fmt: skip
    assert viewer.reloads > reloads
    assert _mast(viewer) is mast  # the same session, reloaded
    assert np.allclose(_link_xyz(viewer, "mast", "mast_top"), (0, 2, 1))  # type: ignore[arg-type]
    wait_for(lambda: model.status.text == "Showing mast", what="its status")


def test_a_missing_file_and_a_xacro_error_are_the_display_s_status(
    viewer: Viewer, tmp_path: Path
) -> None:
    """A file that does not exist says so; once written (a xacro: robomodel's loader reads it,
    RViz 2 reads URDF only) it loads; an error in it is the status with the loader's
    file:line, and the last good robot stays drawn."""
    path = tmp_path / "mast.urdf.xacro"
    _publish_mast_tf(viewer)
    model = _add_file_model(viewer, path)
    wait_for(lambda: "No such file" in model.status.text, what="the missing file's status")
    assert model.status.level is StatusLevel.ERROR
    assert str(path) in model.status.text
    path.write_text(MAST_XACRO)
    wait_for(lambda: model.status.text == "Showing mast", what="the file, once written")
    mast = _mast(viewer)
    assert mast is not None and mast.robot is not None
    assert mast.robot.link_names == ("mast_base",)
    path.write_text(MAST_XACRO.replace("${height}", "${heigth}"))
    wait_for(lambda: model.status.level is StatusLevel.ERROR, what="the xacro error")
    assert model.status.text.startswith(f"URDF: {path}:3:"), model.status.text
    assert "heigth" in model.status.text
    assert _mast(viewer) is mast and mast.display is not None and mast.display.shown


CONFIG = """Visualization Manager:
  Class: ""
  Displays:
    - Alpha: 1
      Class: rviz_default_plugins/RobotModel
      Collision Enabled: false
      Description File: {path}
      Description Source: File
      Description Topic:
        Value: /robot_description
      Enabled: true
      Name: Mast
      TF Prefix: ""
      Update Interval: 0
      Visual Enabled: true
  Global Options:
    Fixed Frame: base_link
"""


def test_a_config_s_robot_model_naming_a_file_loads_that_robot(tmp_path: Path) -> None:
    """The same from a .rviz file, as RViz 2 opens it: the file's robot is drawn from TF, and
    not the viewer's own, which no RobotModel of the file names."""
    from robomodel.viewer.rviz_document import open_rviz_document
    from robomodel.viewer.rviz_model import RvizDialect

    urdf = tmp_path / "mast.urdf"
    urdf.write_text(MAST)
    path = tmp_path / "mast.rviz"
    path.write_text(CONFIG.format(path=urdf))
    document, _ = open_rviz_document(str(path), RvizDialect.ROS2)
    viewer = Viewer(ViewerOptions(sources=(RobotSource(str(PLANAR)),), port=0, rviz=document))
    viewer.start()
    try:
        model = viewer.displays.get("Mast")
        assert model.option("Description File") == str(urdf)
        wait_for(lambda: model.status.text == "No transform from [mast_base] to [base_link]",
                 what="RViz's status: no TF for the mast yet")  # fmt: skip
        _publish_mast_tf(viewer)
        wait_for(lambda: (p := _link_xyz(viewer, "mast", "mast_top")) is not None and np.allclose(p, (0, 2, 1)),
                 what="the mast's top drawn from TF")  # fmt: skip
        wait_for(lambda: model.status.text == "Showing mast", what="its status")
        own = viewer.sessions[0]
        assert own.display is not None and not own.display.shown
    finally:
        viewer.close()
