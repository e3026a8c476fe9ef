"""RobotModel and TF in the Displays panel of a real browser (headless Chromium): a config
without a RobotModel shows no robot, as RViz; the page adds one by type and the arm's orange
gripper appears where the camera must see it; disabling it in the page hides the arm; a TF
display added in the page draws the gripper frame's axes there."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from robomodel.viewer import RobotSource, Viewer, ViewerOptions
from robomodel.viewer.rviz_document import open_rviz_document
from robomodel.viewer.rviz_model import RvizDialect
from tests.conftest import EXAMPLES
from tests.viewer.conftest import gui_row, open_viewer, page_client, save_shot, screenshot, wait_for
from tests.viewer.test_displays_browser import project

pytestmark = pytest.mark.browser

PLANAR = EXAMPLES / "gripper_description/urdf/planar_3dof.urdf"
GRID_ONLY = """Visualization Manager:
  Class: ""
  Displays:
    - Class: rviz_default_plugins/Grid
      Enabled: true
      Name: Grid
  Global Options:
    Fixed Frame: base_link
"""


@pytest.fixture
def grid_only_viewer(tmp_path: Path) -> Iterator[Viewer]:
    path = tmp_path / "grid.rviz"
    path.write_text(GRID_ONLY)
    document, _ = open_rviz_document(str(path), RvizDialect.ROS2)
    viewer = Viewer(ViewerOptions(sources=(RobotSource(str(PLANAR)),), port=0, rviz=document))
    viewer.start()
    # Looking along +y from 1.5 m: the arm lies along +x, its orange gripper at x = 1.0-1.1 m.
    # (the camera's centre at the gripper: the GUI panel covers the page's right side)
    viewer.server.initial_camera.look_at = (1.1, 0.0, 0.0)
    viewer.server.initial_camera.position = (1.1, -1.5, 0.3)
    yield viewer
    viewer.close()


def _fraction(image: np.ndarray, x: float, y: float, test: Any, radius: int = 3) -> float:
    patch = image[int(y) - radius : int(y) + radius, int(x) - radius : int(x) + radius]
    r, g, b = (patch[..., i].astype(int) for i in range(3))
    return float(test(r, g, b).mean())


def _orange(r: Any, g: Any, b: Any) -> Any:
    return (r > 170) & (g > 60) & (g < 190) & (b < 90)


def _grey(r: Any, g: Any, b: Any) -> Any:  # the links' 0.7 grey, shaded (not the white page)
    return (abs(r - g) < 12) & (abs(g - b) < 12) & (r > 60) & (r < 215)


def _seen(page: Any, viewer: Viewer, point: tuple[float, float, float]) -> tuple[float, float]:
    client = page_client(viewer)
    canvas = page.locator("canvas").first.bounding_box()
    wait_for(
        lambda: np.allclose(client.camera.position, (1.1, -1.5, 0.3), atol=1e-3), what="camera"
    )
    x, y = project(client.camera, np.array(point), canvas["width"], canvas["height"])
    return x + canvas["x"], y + canvas["y"]


def _add_by_type(page: Any, class_name: str) -> None:
    gui_row(page, "Display type").locator("input:not([type=hidden])").first.click()
    page.get_by_role("option", name=class_name, exact=True).click()
    page.get_by_role("button", name="Add by type", exact=True).click()


def test_the_page_adds_a_robot_model_to_a_config_without_one(
    grid_only_viewer: Viewer, page: Any
) -> None:
    viewer = grid_only_viewer
    open_viewer(page, viewer.url)
    gripper = _seen(page, viewer, (1.06, 0.0, 0.0))
    link = _seen(page, viewer, (0.25, 0.0, 0.0))
    page.get_by_text("Add display", exact=True).click()
    shot = screenshot(page)
    assert _fraction(shot, *gripper, _orange) == 0.0 and _fraction(shot, *link, _grey) < 0.2
    save_shot(page, "robot_model_none_in_config")
    _add_by_type(page, "RobotModel")
    wait_for(lambda: _fraction(screenshot(page), *gripper, _orange) > 0.3, what="the gripper")
    assert _fraction(screenshot(page), *link, _grey) > 0.3  # the first link too
    save_shot(page, "robot_model_added")
    robot = viewer.displays.displays[-1]
    assert robot.class_name == "RobotModel" and robot.status.text.startswith("Showing")
    page.get_by_text("RobotModel", exact=True).filter(visible=True).first.click()  # its folder
    gui_row(page, "Enabled").locator("input:visible").first.click()
    wait_for(lambda: _fraction(screenshot(page), *gripper, _orange) == 0.0, what="arm hidden")
    assert not robot.enabled
    # TF: the gripper frame's axes (its +z, blue, stands out of the gripper at x = 1 m)
    gui_row(page, "Enabled").locator("input:visible").first.click()
    _add_by_type(page, "TF")
    tip = _seen(page, viewer, (1.0, 0.0, 0.07))

    def blue(r: Any, g: Any, b: Any) -> Any:
        return (b > 150) & (r < 90) & (g < 120)

    wait_for(lambda: _fraction(screenshot(page), *tip, blue, radius=8) > 0.05, what="the z axis")
    save_shot(page, "tf_display_added")
