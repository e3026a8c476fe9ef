"""The Camera display's "View through the camera" in headless Chromium, fed from another
process (tests/viewer/camera_view_publisher.py): a red cube 2 m in front of a camera frame
whose image is plain green.

With "background" the page's centre is the cube's red (the scene over the image) and the
image's corner is green (the image behind); with "overlay" at Overlay Alpha 0.5 the centre is
red and green mixed; turning the view-through off gives the page its camera back.
"""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from robomodel.viewer import Viewer
from tests.viewer import camera_view_publisher as published
from tests.viewer.conftest import open_viewer, save_shot, screenshot, wait_for
from tests.viewer.fed_viewer import viewer_fed_by
from tests.viewer.test_sensor_displays_browser import _look_at_origin
from tests.viewer.test_tools_inprocess import on_loop

pytestmark = pytest.mark.browser


@pytest.fixture
def camera_viewer(tmp_path: Path) -> Iterator[Viewer]:
    with viewer_fed_by("tests.viewer.camera_view_publisher", tmp_path) as viewer:
        yield viewer


def _drop_software_webgl_toast(page: Any) -> None:
    """viser's "Software WebGL rendering" notice sits over the view's top left (headless
    Chromium renders in software), where the image's corner is looked for."""
    page.evaluate(
        """() => { for (const toast of document.querySelectorAll('.mantine-Notification-root'))
            if (toast.textContent.includes('Software WebGL rendering')) toast.remove(); }"""
    )


def _pixel(image: np.ndarray, uv: tuple[float, float], radius: int = 2) -> np.ndarray:
    """The mean colour around page pixel ``uv``."""
    u, v = round(uv[0]), round(uv[1])
    return image[v - radius : v + radius + 1, u - radius : u + radius + 1].reshape(-1, 3).mean(axis=0)  # fmt: skip


def _red(rgb: np.ndarray) -> bool:
    return bool(rgb[0] > 100 and rgb[0] - max(rgb[1], rgb[2]) > 60)


def _green(rgb: np.ndarray) -> bool:
    return bool(rgb[1] > 200 and rgb[1] - max(rgb[0], rgb[2]) > 150)


def _red_green_mix(rgb: np.ndarray) -> bool:
    """Red and green both well present (an alpha 0.5 green image over a red face), no blue."""
    return bool(rgb[0] > 50 and rgb[1] > 90 and rgb[1] < 200 and rgb[2] < 60)


def test_view_through_the_camera_background_and_overlay(camera_viewer: Viewer, page: Any) -> None:
    viewer = camera_viewer
    open_viewer(page, viewer.url)
    camera = _look_at_origin(viewer)  # the user's camera, given back at the end
    before = (camera.position.copy(), camera.fov)
    values = {"Topic": "/camera/image_raw", "Image Rendering": "background"}
    display = on_loop(viewer, lambda: viewer.displays_panel.add("Camera", name="Camera", values=values))  # fmt: skip
    on_loop(viewer, lambda: viewer.displays_panel.add("Marker", name="Cube", values={"Topic": "/cube"}))  # fmt: skip
    wait_for(lambda: "not rendered over" in display.status.text, what=f"the frustum ({display.status.text})")  # fmt: skip
    on_loop(viewer, lambda: display.set_view_through(True))
    wait_for(lambda: display.status.level.value == "ok" and "looks through the camera" in display.status.text,
             what=f"the view-through status (have {display.status.text})")  # fmt: skip

    fov = 2 * np.arctan(published.IMAGE_SIZE_PX / (2 * published.FOCAL_PX))
    wait_for(lambda: np.allclose(camera.position, published.CAMERA_XYZ, atol=1e-3)
             and abs(camera.fov - fov) < 1e-3, what="the page's camera at the camera frame")  # fmt: skip
    # the 3D view fills the page (the GUI floats over its right side); the canvas element's
    # box can be larger than the page while viser adapts its pixel ratio
    height, width = screenshot(page).shape[:2]
    centre = (width / 2, height / 2)
    # the square image fills the page's height: 80% of the way to its top-left corner
    half = 0.8 * height / 2
    corner = (centre[0] - half, centre[1] - half)

    def seen(centre_ok: Any, corner_ok: Any) -> bool:
        _drop_software_webgl_toast(page)
        shot = screenshot(page)
        return bool(centre_ok(_pixel(shot, centre)) and corner_ok(_pixel(shot, corner)))

    wait_for(lambda: seen(_red, _green),
             what=lambda: f"red at {centre}, green at {corner} (have {_pixel(shot := screenshot(page), centre)}, {_pixel(shot, corner)})")  # fmt: skip
    save_shot(page, "camera_view_background")

    on_loop(viewer, lambda: display.set_option("Image Rendering", "overlay"))
    wait_for(
        lambda: seen(_red_green_mix, lambda _rgb: True),
        what=lambda: f"red and green mixed at {centre} (have {_pixel(screenshot(page), centre)})",
    )
    save_shot(page, "camera_view_overlay")

    on_loop(viewer, lambda: display.set_view_through(False))
    wait_for(lambda: np.allclose(camera.position, before[0], atol=1e-3) and abs(camera.fov - before[1]) < 1e-3,
             what=lambda: f"the user's camera back at {before} (have {camera.position}, {camera.fov})")  # fmt: skip
    wait_for(lambda: "not rendered over" in display.status.text, what="the frustum again")
