"""A config with displays saved from the page opens in Debian's ``rviz -d``.

The page (headless Chromium) adds a Marker and a MarkerArray display on a ROS 1 graph and clicks
Save Config; rviz under Xvfb opens the file, draws the red cube Debian's ``rostopic pub`` sends
(its screenshot has the cube's red), and its log names no display class it could not load.
robomodel reads the file back with the same displays and options.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from robomodel.viewer import RobotSource, Viewer, ViewerOptions
from robomodel.viewer.rviz_config import read_rviz_file
from robomodel.viewer.rviz_document import open_rviz_document
from robomodel.viewer.rviz_model import RvizDialect
from tests.conftest import EXAMPLES
from tests.ros1wire.conftest import Ros1, has, ros1  # noqa: F401  (the fixture)
from tests.ros1wire.rviz_window import rviz_until, xvfb
from tests.viewer.conftest import gui_row, open_viewer, save_shot, wait_for

pytestmark = pytest.mark.browser

PLANAR = EXAMPLES / "gripper_description/urdf/planar_3dof.urdf"
RED_CUBE = (
    "{header: {frame_id: base_link}, ns: cubes, id: 1, type: 1, action: 0, "
    "pose: {position: {x: 1.0, y: 0.0, z: 0.0}, orientation: {w: 1.0}}, "
    "scale: {x: 0.4, y: 0.4, z: 0.4}, color: {r: 1.0, g: 0.0, b: 0.0, a: 1.0}}"
)


def _red_pixels(png: Path) -> int:
    from PIL import Image

    rgb = np.asarray(Image.open(png).convert("RGB")).astype(int)
    r, g, b = rgb[..., 0], rgb[..., 1], rgb[..., 2]
    return int(((r > 100) & (r > 3 * g) & (r > 3 * b)).sum())


def _add_by_type(page: Any, class_name: str) -> None:
    gui_row(page, "Display type").locator("input:not([type=hidden])").first.click()
    page.get_by_role("option", name=class_name, exact=True).click()
    page.get_by_role("button", name="Add by type", exact=True).click()


def _save_from_the_page(ros1: Ros1, config: Path, page: Any) -> list[dict[str, Any]]:  # noqa: F811
    """The page on a ROS 1 graph adds Marker (which receives the red cube) and MarkerArray and
    saves ``config``; the displays' option values."""
    os.environ["ROS_IP"] = "127.0.0.1"
    document, _ = open_rviz_document(str(config), RvizDialect.ROS1)
    source = RobotSource(str(PLANAR))
    viewer = Viewer(ViewerOptions(sources=(source,), port=0, bus="ros1", master=ros1.uri, rviz=document))  # fmt: skip
    viewer.start()
    try:
        viewer.server.initial_camera.look_at = (0.0, 0.0, 0.0)
        viewer.server.initial_camera.position = (0.0, -4.0, 1.0)
        open_viewer(page, viewer.url)
        page.get_by_text("Add display", exact=True).click()
        _add_by_type(page, "Marker")
        wait_for(lambda: len(viewer.displays.displays) == 4, what="the Marker display")
        _add_by_type(page, "MarkerArray")
        wait_for(lambda: len(viewer.displays.displays) == 5, what="the MarkerArray display")
        marker = viewer.displays.displays[3]  # after Grid, RobotModel, TF; it hears rostopic pub
        wait_for(lambda: marker.store.markers, what="the red cube over ROS 1's wire")
        wait_for(lambda: marker.status.text.endswith("messages received"), what="Ok status")
        page.get_by_role("button", name="Save Config", exact=True).click()
        wait_for(config.exists, what=f"{config} written")
        save_shot(page, "displays_saved_for_rviz")
        return [dict(d.values) for d in viewer.displays.displays]
    finally:
        viewer.close()
        os.environ.pop("ROS_IP", None)


def test_rviz_opens_the_displays_saved_from_the_page(ros1: Ros1, tmp_path: Path, page: Any) -> None:  # noqa: F811
    if not (has("Xvfb") and Path("/usr/bin/rviz").exists()):
        pytest.fail("rviz and Xvfb are missing: tools/system-deps test installs them")

    ros1.roscore()
    pub = ["/usr/bin/rostopic", "pub", "-r", "5", "/visualization_marker"]
    publisher = ros1.start([*pub, "visualization_msgs/Marker", RED_CUBE])
    config = tmp_path / "markers.rviz"
    values = _save_from_the_page(ros1, config, page)
    saved = read_rviz_file(config)
    assert [d.class_name for d in saved.displays][-2:] == ["rviz/Marker", "rviz/MarkerArray"]
    assert saved.displays[-2].settings["Marker Topic"] == "/visualization_marker"
    display = xvfb(ros1, "1280x900x24")
    log = tmp_path / "rviz.log"
    kept = Path(os.environ.get("ROBOMODEL_SCREENSHOTS", str(tmp_path))) / "rviz_markers.png"

    def cube_drawn(shot: Path) -> bool:
        assert publisher.poll() is None, "rostopic pub ended"
        return _red_pixels(shot) > 200

    shot = rviz_until(ros1, config, display, log, cube_drawn, 90)
    kept.parent.mkdir(parents=True, exist_ok=True)  # for the reader: rviz's window as seen last
    kept.write_bytes(shot.read_bytes())
    assert _red_pixels(shot) > 200, f"no red cube in rviz's window ({kept})"
    text = log.read_text()
    for complaint in ("failed to load", "PluginlibFactory", "does not exist"):
        assert complaint not in text, text
    # Read back by robomodel: the same displays with the same options.
    document, _ = open_rviz_document(str(config), RvizDialect.ROS1)
    again = Viewer(ViewerOptions(sources=(RobotSource(str(PLANAR)),), port=0, rviz=document))
    again.start()
    try:
        assert [dict(d.values) for d in again.displays.displays] == values
    finally:
        again.close()
