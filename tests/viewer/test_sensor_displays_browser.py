"""PointCloud2, Map, Image, Camera, Pose, Odometry and Path displays in headless Chromium, fed
from another process (tests/viewer/display_publisher.py) over the Zenoh bus.

The page's camera is set to look down at the fixed frame's origin; each cloud point and map
cell is projected with that camera (viser's OpenCV convention) and its pixel in the
screenshot must have the message's colour. The Image display's image area must show the 4x4
checkerboard without a click, and every display's status must say what RViz's would.
"""

from __future__ import annotations

import io
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from PIL import Image

from robomodel.viewer import Viewer
from tests.viewer import display_publisher as published
from tests.viewer.conftest import open_viewer, page_client, save_shot, screenshot, wait_for
from tests.viewer.fed_viewer import viewer_fed_by
from tests.viewer.test_tools_inprocess import on_loop

pytestmark = pytest.mark.browser


@pytest.fixture
def fed_viewer(tmp_path: Path) -> Iterator[Viewer]:
    with viewer_fed_by("tests.viewer.display_publisher", tmp_path) as viewer:
        yield viewer


def _statuses(viewer: Viewer) -> dict[str, str]:
    return on_loop(viewer, lambda: {d.name: d.status.text for d in viewer.displays.displays})


def _look_at_origin(viewer: Viewer, position: tuple[float, float, float] = (0.0, -6.0, 8.0)) -> Any:  # fmt: skip
    """Put the page's camera at ``position`` looking at the origin (+z up), and wait until the
    page reports that pose back.

    viser's setters change the server's copy at once, and each report from the page replaces
    it: a report the page sent before it took the new pose (on a loaded machine, a round trip
    can take a second) would put the old pose back. Only a report of the new pose says that
    every older one has arrived (one websocket, in order) and the page has taken it."""
    from scipy.spatial.transform import Rotation

    camera = page_client(viewer).camera
    forward = -np.asarray(position) / np.linalg.norm(position)
    reports: list[tuple[np.ndarray, np.ndarray]] = []

    async def on_report(reported: Any) -> None:  # async: runs on viser's loop, in order
        reports.append((np.array(reported.position), np.array(reported.wxyz)))

    camera.on_update(on_report)
    camera.position = position  # first: viser's position setter carries look_at along
    camera.look_at = (0.0, 0.0, 0.0)

    def settled() -> bool:
        if not reports:
            return False
        xyz, (w, x, y, z) = reports[-1]
        R = Rotation.from_quat([x, y, z, w]).as_matrix()
        return bool(np.allclose(xyz, position, atol=1e-3) and R[:, 2] @ forward > 0.9999)

    wait_for(settled, what="the page's camera to look at the origin")
    return camera


def _project(camera: Any, canvas: dict[str, float], points: np.ndarray) -> np.ndarray:
    """Page pixels (n, 2) of world points with viser's camera (OpenCV: +z forward, +y down)."""
    from scipy.spatial.transform import Rotation

    w, x, y, z = camera.wxyz
    R = Rotation.from_quat([x, y, z, w]).as_matrix()
    p = (np.asarray(points, float) - camera.position) @ R  # R^T (p - t), row vectors
    f = (canvas["height"] / 2) / np.tan(camera.fov / 2)
    u = canvas["x"] + canvas["width"] / 2 + f * p[:, 0] / p[:, 2]
    v = canvas["y"] + canvas["height"] / 2 + f * p[:, 1] / p[:, 2]
    return np.stack([u, v], axis=1)


def _colour_near(image: np.ndarray, uv: np.ndarray, rgb: tuple[int, int, int], radius: int = 3) -> bool:  # fmt: skip
    """Whether some pixel within ``radius`` of ``uv`` has colour ``rgb`` (within 40)."""
    u, v = round(float(uv[0])), round(float(uv[1]))
    patch = image[v - radius : v + radius + 1, u - radius : u + radius + 1].astype(int)
    return bool((np.abs(patch - np.array(rgb)).max(axis=2) < 40).any())


def test_cloud_map_image_camera_and_pose_displays(fed_viewer: Viewer, page: Any) -> None:
    viewer = fed_viewer
    open_viewer(page, viewer.url)
    adds = {
        "Cloud": ("PointCloud2", {"Topic": "/cloud", "Size (m)": 0.25}),
        "Map": ("Map", {"Topic": "/map", "Alpha": 1.0}),
        "Image": ("Image", {"Topic": "/camera/image_raw"}),
        "Camera": ("Camera", {"Topic": "/camera/image_raw"}),
        "Pose": ("Pose", {"Topic": "/pose"}),
        "Odometry": ("Odometry", {"Topic": "/odom", "Covariance/Value": False}),
        "Path": ("Path", {"Topic": "/path"}),
    }
    for name, (kind, values) in adds.items():
        on_loop(viewer, lambda k=kind, n=name, v=values: viewer.displays_panel.add(k, name=n, values=v))  # fmt: skip
    expected = {
        "Cloud": "Showing [3] points from [1] messages",
        "Map": "Map OK: 4 X 4 map @ 0.5 m/pix",
        "Pose": "Frame [nowhere] does not exist",
        "Odometry": "1 arrows kept",
    }
    wait_for(
        lambda: all(_statuses(viewer).get(n) == t for n, t in expected.items()),
        what=f"the statuses {expected} (have {_statuses(viewer)})",
    )
    wait_for(lambda: "images received; showing 4x4" in _statuses(viewer)["Image"], what="image")
    camera_status = _statuses(viewer)["Camera"]
    assert "scene is not rendered over the image" in camera_status, camera_status

    camera = _look_at_origin(viewer)
    canvas = page.locator("canvas").first.bounding_box()
    points = np.array([p for p, _ in published.CLOUD_POINTS])
    colours = [((c >> 16) & 255, (c >> 8) & 255, c & 255) for _, c in published.CLOUD_POINTS]
    cells = np.array([(published.MAP_ORIGIN[0] + (i + 0.5) * published.MAP_RESOLUTION,
                       published.MAP_ORIGIN[1] + (j + 0.5) * published.MAP_RESOLUTION, 0.0)
                      for j in range(4) for i in range(4)])  # fmt: skip
    palette = {0: (255, 255, 255), 100: (0, 0, 0), -1: (0x70, 0x89, 0x86)}
    cell_colours = [palette[int(v)] for v in published.MAP_CELLS.ravel()]

    (odom_shaft, path_middle) = _project(camera, canvas, np.array([
        (published.ODOM_XY[0] + 0.5, published.ODOM_XY[1], 0.0),
        ((published.PATH_XY[0][0] + published.PATH_XY[1][0]) / 2, published.PATH_XY[0][1], 0.0),
    ]))  # fmt: skip

    def all_seen() -> bool:
        shot = screenshot(page)
        # arrows are lit (shaded): RViz's 255; 25; 0 as a red hue, the path's 25; 255; 0 green
        if not (_hue_near(shot, odom_shaft, 0) and _hue_near(shot, path_middle, 1)):
            return False
        cloud_ok = all(_colour_near(shot, uv, c) for uv, c in zip(_project(camera, canvas, points), colours, strict=True))  # fmt: skip
        map_ok = all(_colour_near(shot, uv, c, 2) for uv, c in zip(_project(camera, canvas, cells), cell_colours, strict=True))  # fmt: skip
        return cloud_ok and map_ok

    where = {"points": _project(camera, canvas, points).round().tolist(), "canvas": canvas,
             "camera": (camera.position.tolist(), camera.wxyz.tolist(), camera.fov)}  # fmt: skip
    wait_for(all_seen, what=f"the cloud's points and the map's cells at their pixels {where}")
    shot_path = save_shot(page, "displays_cloud_map")
    assert shot_path.exists()

    # RViz's Image display has a panel of its own, shown at once: no folder to open
    wait_for(lambda: _checkerboard_seen(_panel_image(page)), what="the checkerboard in the panel")
    save_shot(page, "displays_image_panel")


def _hue_near(image: np.ndarray, uv: np.ndarray, channel: int, radius: int = 3) -> bool:
    """Whether some pixel within ``radius`` of ``uv`` is dominated by ``channel`` (R=0, G=1)."""
    u, v = round(float(uv[0])), round(float(uv[1]))
    patch = image[v - radius : v + radius + 1, u - radius : u + radius + 1].astype(int)
    others = np.delete(patch, channel, axis=2).max(axis=2)
    return bool(((patch[..., channel] > 120) & (patch[..., channel] - others > 40)).any())


def _panel_image(page: Any) -> Any:
    """The largest <img> in the page (the Image display's; the other is viser's logo)."""
    images = page.locator("img")
    boxes = [(images.nth(i).bounding_box(), i) for i in range(images.count())]
    sized = [(b["width"] * b["height"], i) for b, i in boxes if b]
    return images.nth(max(sized)[1]) if sized else None


def _checkerboard_seen(element: Any) -> bool:
    if element is None:
        return False
    element.scroll_into_view_if_needed()
    image = np.asarray(Image.open(io.BytesIO(element.screenshot())).convert("RGB")).astype(int)
    h, w, _ = image.shape
    if h < 8 or w < 8:
        return False
    centres = image[(np.arange(4) * h // 4 + h // 8)][:, (np.arange(4) * w // 4 + w // 8)]
    expected = np.where(published.BOARD[..., None], (255, 0, 0), (0, 0, 255))
    return bool(np.abs(centres - expected).max() < 40)
