"""The sensor and navigation displays saved in a ROS 1 config open in Debian's ``rviz -d``.

A viewer adds PointCloud2, Image, Camera, Map, Path, Pose, PoseArray, PoseWithCovariance,
Odometry and Wrench (RViz 1's ``rviz/WrenchStamped``) displays and saves a ROS 1 config. A display of a class no rviz has is appended as
the last one: rviz loads displays in order, so its "failed to load" line in rviz's log says
that every display before it was tried; none of ours may be named in such a line. robomodel
reads the file back with the same displays and options.
"""

from __future__ import annotations

from pathlib import Path

import pytest
import yaml

from robomodel.viewer import RobotSource, Viewer, ViewerOptions
from robomodel.viewer.rviz_document import open_rviz_document
from robomodel.viewer.rviz_model import RvizDialect
from tests.conftest import EXAMPLES
from tests.ros1wire.conftest import Ros1, has, ros1  # noqa: F401  (the fixture)
from tests.ros1wire.rviz_window import rviz_until, xvfb
from tests.viewer.test_tools_inprocess import on_loop

pytestmark = pytest.mark.browser

PLANAR = EXAMPLES / "gripper_description/urdf/planar_3dof.urdf"
OURS = {
    "PointCloud2": {"Topic": "/points", "Decay Time": 2.0, "Color Transformer": "AxisColor"},
    "Image": {"Topic": "/camera/image_raw"},
    "Camera": {"Topic": "/camera/image_raw"},
    "Map": {"Topic": "/map", "Color Scheme": "costmap"},
    "Path": {"Topic": "/plan", "Offset/Z": 0.5},
    "Pose": {"Topic": "/goal", "Shape": "Axes"},
    "PoseArray": {"Topic": "/particles"},
    "PoseWithCovariance": {"Topic": "/amcl_pose"},
    "Odometry": {"Topic": "/odom", "Keep": 20, "Shape/Value": "Axes"},
    "Wrench": {"Topic": "/wrench"},
}
CONTROL = "rviz/NoSuchDisplayForThisTest"


def _save(path: Path) -> list[dict[str, object]]:
    document, _ = open_rviz_document(str(path), RvizDialect.ROS1)
    viewer = Viewer(ViewerOptions(sources=(RobotSource(str(PLANAR)),), port=0, rviz=document))
    viewer.start()
    try:
        for kind, values in OURS.items():
            on_loop(viewer, lambda k=kind, v=values: viewer.displays_panel.add(k, values=v))
        assert viewer.config_panel.save(str(path))
        return [dict(d.values) for d in viewer.displays.displays]
    finally:
        viewer.close()


def test_rviz_opens_the_sensor_displays_saved_by_robomodel(ros1: Ros1, tmp_path: Path) -> None:  # noqa: F811
    if not (has("Xvfb") and Path("/usr/bin/rviz").exists()):
        pytest.fail("rviz and Xvfb are missing: tools/system-deps test installs them")
    config = tmp_path / "sensors.rviz"
    values = _save(config)
    tree = yaml.safe_load(config.read_text())
    displays = tree["Visualization Manager"]["Displays"]
    expected = [f"rviz/{'WrenchStamped' if k == 'Wrench' else k}" for k in OURS]
    assert [d["Class"] for d in displays][-len(OURS) :] == expected
    (odometry,) = [d for d in displays if d["Class"] == "rviz/Odometry"]
    assert odometry["Shape"]["Value"] == "Axes" and odometry["Keep"] == 20
    (image,) = [d for d in displays if d["Class"] == "rviz/Image"]
    assert image["Image Topic"] == "/camera/image_raw"  # RViz 1's key
    with_control = tmp_path / "with_control.rviz"
    displays.append({"Class": CONTROL, "Enabled": True, "Name": "Control", "Value": True})
    with_control.write_text(yaml.safe_dump(tree, sort_keys=False))

    ros1.roscore()
    display = xvfb(ros1, "1024x768x24")
    log = tmp_path / "rviz.log"
    # rviz got to the last display
    rviz_until(ros1, with_control, display, log, lambda _shot: CONTROL in log.read_text(), 90)
    assert CONTROL in log.read_text(), f"rviz never reached the last display: {log.read_text()}"
    complaints = [line for line in log.read_text().splitlines() if "rviz/" in line and CONTROL not in line]  # fmt: skip
    assert not complaints, "\n".join(complaints)

    document, _ = open_rviz_document(str(config), RvizDialect.ROS1)
    again = Viewer(ViewerOptions(sources=(RobotSource(str(PLANAR)),), port=0, rviz=document))
    again.start()
    try:
        assert [dict(d.values) for d in again.displays.displays] == values
    finally:
        again.close()
