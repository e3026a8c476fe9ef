"""The Displays panel in a real browser (headless Chromium, real time), the viewer in this process.

Another process (``robomodel topic pub``) publishes a red cube marker 1 m ahead of base_link on
the Zenoh bus; the page adds a Marker display from the live graph ("Add by topic"), and the
screenshot must show red where the camera sees that point (its projection through the page's
camera) and not where the mirror point is. The display's status line says Ok; switching the
namespace off in the page hides the cube.
"""

from __future__ import annotations

import math
import subprocess
from collections.abc import Iterator
from typing import Any

import numpy as np
import pytest

from robomodel.viewer import RobotSource, Viewer, ViewerOptions
from tests.conftest import EXAMPLES, ROBOMODEL, unique_domain
from tests.timing import scaled
from tests.viewer.conftest import (
    gui_row,
    new_page,
    open_viewer,
    page_client,
    save_shot,
    screenshot,
    wait_for,
)
from tests.viewer.test_tools_inprocess import on_loop

pytestmark = [pytest.mark.browser, pytest.mark.xdist_group("displays_browser")]

PLANAR = EXAMPLES / "gripper_description/urdf/planar_3dof.urdf"
RED_CUBE = (
    "{header: {frame_id: base_link}, ns: cubes, id: 1, type: 1, action: 0, "
    "pose: {position: {x: 1.0, y: 0.0, z: 0.0}, orientation: {w: 1.0}}, "
    "scale: {x: 0.3, y: 0.3, z: 0.3}, color: {r: 1.0, g: 0.0, b: 0.0, a: 1.0}}"
)


@pytest.fixture(scope="module")
def zenoh_viewer() -> Iterator[tuple[Viewer, str]]:
    domain = unique_domain()
    source = RobotSource(str(PLANAR))
    viewer = Viewer(ViewerOptions(sources=(source,), port=0, bus="zenoh", domain_id=int(domain)))
    viewer.start()
    # The camera looks along +y from 4 m: base_link's +x is to the right of the centre.
    viewer.fixed_dropdown.value = "base_link"
    viewer.server.initial_camera.look_at = (0.0, 0.0, 0.0)
    viewer.server.initial_camera.position = (0.0, -4.0, 1.0)
    yield viewer, domain
    viewer.close()


@pytest.fixture(scope="module")
def red_cube_publisher(zenoh_viewer: tuple[Viewer, str]) -> Iterator[subprocess.Popen[str]]:
    _viewer, domain = zenoh_viewer
    argv = ["topic", "pub", "-r", "5", "/visualization_marker", "visualization_msgs/msg/Marker"]
    proc = subprocess.Popen(
        [*ROBOMODEL, *argv, RED_CUBE, "--bus", "zenoh", "--domain-id", domain],
        stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True, start_new_session=True,
    )  # fmt: skip
    yield proc
    proc.terminate()
    proc.wait(scaled(10))


@pytest.fixture(scope="module")
def shared_page(browser: Any, zenoh_viewer: tuple[Viewer, str]) -> Iterator[Any]:
    """One page on the module's viewer for both tests: a page's first frames (software WebGL
    compiling its shaders, the scene's first load) cost more CPU than a test's own work."""
    viewer, _domain = zenoh_viewer
    with new_page(browser) as page:
        open_viewer(page, viewer.url)
        yield page


@pytest.fixture
def page(shared_page: Any, zenoh_viewer: tuple[Viewer, str]) -> Iterator[Any]:
    """The module's page; the displays a test adds are removed after it (the defaults kept)."""
    viewer, _domain = zenoh_viewer
    yield shared_page
    panel = viewer.displays_panel

    def remove_added() -> None:
        for row in list(panel.rows[3:]):  # after Grid, RobotModel, TF
            panel.remove(row)

    on_loop(viewer, remove_added)
    wait_for(lambda: len(viewer.displays.displays) == 3, what="the test's displays removed")


def _open_add_display(page: Any) -> None:
    """Open the Add display folder (a click on an open one would close it)."""
    if not gui_row(page, "Display type").filter(visible=True).count():
        page.get_by_text("Add display", exact=True).click()


def project(camera: Any, point: np.ndarray, width: float, height: float) -> tuple[float, float]:
    """Where three.js's perspective camera (vertical ``fov``, +z up) draws ``point`` [px]."""
    position, look_at = np.asarray(camera.position), np.asarray(camera.look_at)
    forward = (look_at - position) / np.linalg.norm(look_at - position)
    right = np.cross(forward, (0.0, 0.0, 1.0))
    right /= np.linalg.norm(right)
    up = np.cross(right, forward)
    d = point - position
    depth, half = float(d @ forward), math.tan(camera.fov / 2)
    x_ndc = float(d @ right) / (depth * half * width / height)
    y_ndc = float(d @ up) / (depth * half)
    return (x_ndc + 1) / 2 * width, (1 - y_ndc) / 2 * height


def red_fraction(image: np.ndarray, x: float, y: float, radius: int = 6) -> float:
    patch = image[int(y) - radius : int(y) + radius, int(x) - radius : int(x) + radius].astype(int)
    r, g, b = patch[..., 0], patch[..., 1], patch[..., 2]
    return float(((r > 100) & (r > 2 * g) & (r > 2 * b)).mean())


def test_a_red_cube_marker_from_another_process_is_drawn_where_the_camera_sees_it(
    zenoh_viewer: tuple[Viewer, str], red_cube_publisher: subprocess.Popen[str], page: Any
) -> None:
    viewer, _domain = zenoh_viewer
    _open_add_display(page)
    entry = "/visualization_marker (Marker)"
    wait_for(lambda: entry in viewer.displays_panel.topic_dropdown.options, what="the topic")
    gui_row(page, "Topic").locator("input:not([type=hidden])").first.click()
    page.get_by_role("option", name=entry, exact=True).click()
    page.get_by_role("button", name="Add by topic", exact=True).click()
    wait_for(
        lambda: len(viewer.displays.displays) == 4,
        what="the display added (after Grid, RobotModel, TF)",
    )
    display = viewer.displays.displays[3]
    assert (display.class_name, display.name, display.topic) == ("Marker", "/visualization_marker", "/visualization_marker")  # fmt: skip
    client = page_client(viewer)
    canvas = page.locator("canvas").first.bounding_box()
    wait_for(lambda: np.allclose(client.camera.position, (0, -4, 1), atol=1e-3), what="camera")
    x, y = project(client.camera, np.array([1.0, 0.0, 0.0]), canvas["width"], canvas["height"])
    mx, my = project(client.camera, np.array([-1.0, 0.0, 0.0]), canvas["width"], canvas["height"])
    x, y, mx, my = x + canvas["x"], y + canvas["y"], mx + canvas["x"], my + canvas["y"]

    wait_for(lambda: red_fraction(screenshot(page), x, y) > 0.8, what="red where the cube is")
    shot = screenshot(page)
    save_shot(page, "marker_red_cube")
    assert red_fraction(shot, mx, my) == 0.0  # not mirrored, not everywhere
    page.get_by_text("/visualization_marker", exact=True).click()  # the display's folder
    wait_for(lambda: "✓ Ok" in page.content() and "messages received" in page.content(), what="status")  # fmt: skip
    # Namespaces: switching "cubes" off hides the cube.
    page.get_by_text("Namespaces", exact=True).click()
    page.get_by_text("cubes", exact=True).click()
    wait_for(lambda: red_fraction(screenshot(page), x, y) == 0.0, what="the cube hidden")
    save_shot(page, "marker_namespace_off")
    wait_for(lambda: display.option("Namespaces") == {"cubes": False}, what="the option stored")


def _cube_seen(page: Any, viewer: Viewer) -> tuple[float, float]:
    """Where the red cube must be on the page (the page's camera as set by the fixture)."""
    client = page_client(viewer)
    canvas = page.locator("canvas").first.bounding_box()
    wait_for(lambda: np.allclose(client.camera.position, (0, -4, 1), atol=1e-3), what="camera")
    x, y = project(client.camera, np.array([1.0, 0.0, 0.0]), canvas["width"], canvas["height"])
    return x + canvas["x"], y + canvas["y"]


def test_a_display_is_disabled_renamed_retargeted_and_removed_in_the_page(
    zenoh_viewer: tuple[Viewer, str], red_cube_publisher: subprocess.Popen[str], page: Any
) -> None:
    viewer, _domain = zenoh_viewer
    _open_add_display(page)
    gui_row(page, "Display type").locator("input:not([type=hidden])").first.click()
    page.get_by_role("option", name="Marker", exact=True).click()
    page.get_by_role("button", name="Add by type", exact=True).click()
    wait_for(
        lambda: len(viewer.displays.displays) == 4,
        what="the display added (after Grid, RobotModel, TF)",
    )
    display = viewer.displays.displays[3]
    x, y = _cube_seen(page, viewer)
    wait_for(lambda: red_fraction(screenshot(page), x, y) > 0.8, what="the cube")
    page.get_by_text("Marker", exact=True).first.click()  # the folder (then the list's option)
    gui_row(page, "Enabled").locator("input:visible").first.click()
    wait_for(lambda: red_fraction(screenshot(page), x, y) == 0.0, what="the cube hidden")
    assert not display.enabled and "Disabled" in page.content()
    gui_row(page, "Enabled").locator("input:visible").first.click()
    wait_for(lambda: red_fraction(screenshot(page), x, y) > 0.8, what="the cube back")
    # :visible: the Grid and TF displays' folders (collapsed) have their own Enabled and Name
    # rows, and the RobotModel's (open) its Name row above
    name = gui_row(page, "Name").locator("input:not([type=hidden]):visible").first
    name.fill("Cubes")
    name.press("Enter")
    page.get_by_text("Cubes", exact=True).wait_for()
    assert display.name == "Cubes" and display.root == "/displays/Cubes"
    topic = gui_row(page, "Topic").locator("input:not([type=hidden])").last
    topic.fill("/nothing_here")
    topic.press("Enter")
    # a message of the old topic already queued must not count for the new one
    wait_for(lambda: "No messages received" in page.content(), what="the new topic's status")
    assert red_fraction(screenshot(page), x, y) == 0.0
    save_shot(page, "marker_display_retargeted")
    page.get_by_role("button", name="Remove", exact=True).click()
    wait_for(
        lambda: len(viewer.displays.displays) == 3, what="the display removed (the defaults kept)"
    )
    wait_for(lambda: page.get_by_text("Cubes", exact=True).count() == 0, what="its folder gone")
