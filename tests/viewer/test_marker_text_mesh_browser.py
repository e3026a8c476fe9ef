"""Text and mesh-resource markers in headless Chromium, fed from another process
(tests/viewer/marker_publisher.py) over the Zenoh bus.

RViz draws a TEXT_VIEW_FACING marker in the marker's colour and alpha, ``scale.z`` high,
turned to the camera; a MESH_RESOURCE marker with ``mesh_use_embedded_materials`` in the
mesh's own texture (tinted by a non-zero colour, as RViz 2 does), and without it in the
marker's colour. The screenshot is checked at the
pixels where the page's camera sees each one.
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

import numpy as np
import pytest

from robomodel.viewer import Viewer
from tests.viewer import marker_publisher as published
from tests.viewer.conftest import new_page, open_viewer, save_shot, screenshot, wait_for
from tests.viewer.fed_viewer import viewer_fed_by
from tests.viewer.test_sensor_displays_browser import _look_at_origin, _project
from tests.viewer.test_tools_inprocess import on_loop

pytestmark = [pytest.mark.browser, pytest.mark.xdist_group("marker_text_mesh_browser")]


@pytest.fixture(scope="module")
def fed_page(browser: Any, tmp_path_factory: pytest.TempPathFactory) -> Iterator[tuple[Viewer, Any]]:  # fmt: skip
    """One viewer fed by the marker publisher and one page on it, for the module's tests: a
    page's first frames (software WebGL compiling its shaders, the scene's first load) cost
    more CPU than a test's own work. Each test adds its display and sets the camera it looks
    through; :func:`marker_viewer` removes the display after it."""
    tmp_path = tmp_path_factory.mktemp("markers")
    with (
        viewer_fed_by("tests.viewer.marker_publisher", tmp_path, str(tmp_path)) as viewer,
        new_page(browser) as page,
    ):
        open_viewer(page, viewer.url)
        yield viewer, page


@pytest.fixture
def marker_viewer(fed_page: tuple[Viewer, Any]) -> Iterator[tuple[Viewer, Any]]:
    """The module's viewer and page; the displays a test adds are removed after it."""
    viewer, _page = fed_page
    panel = viewer.displays_panel
    before = on_loop(viewer, lambda: len(panel.rows))
    yield fed_page

    def remove_added() -> None:
        for row in list(panel.rows[before:]):
            panel.remove(row)

    on_loop(viewer, remove_added)


def _statuses(viewer: Viewer) -> dict[str, str]:
    return on_loop(viewer, lambda: {d.name: d.status.text for d in viewer.displays.displays})


def _box(uv: np.ndarray, half_px: float) -> tuple[slice, slice]:
    u, v, h = round(float(uv[0])), round(float(uv[1])), round(half_px)
    return slice(v - h, v + h + 1), slice(u - h, u + h + 1)


def _pure(patch: np.ndarray, rgb: tuple[int, int, int], tolerance: int = 30) -> np.ndarray:
    return np.abs(patch.astype(int) - np.array(rgb)).max(axis=2) < tolerance


def _text_ink(shot: np.ndarray, camera: Any, canvas: dict[str, float], xyz: tuple[float, float, float]) -> tuple[int, int, float]:  # fmt: skip
    """The green text's ink around ``xyz``: its height and width [px], and the projected
    height of ``TEXT_HEIGHT_M`` there [px]."""
    h = published.TEXT_HEIGHT_M
    top, bottom = _project(camera, canvas, np.asarray(xyz) + np.array([[0, 0, h / 2], [0, 0, -h / 2]]))  # fmt: skip
    line_px = float(np.linalg.norm(top - bottom))
    centre = (top + bottom) / 2
    rows, cols = _box(centre, 2 * line_px)
    ink = _pure(shot[rows, cols], (0, 255, 0))
    if not ink.any():
        return 0, 0, line_px
    r, c = np.flatnonzero(ink.any(axis=1)), np.flatnonzero(ink.any(axis=0))
    return int(r[-1] - r[0] + 1), int(c[-1] - c[0] + 1), line_px


def test_text_markers_are_drawn_in_their_colour_alpha_and_height_facing_the_camera(
    marker_viewer: tuple[Viewer, Any],
) -> None:
    viewer, page = marker_viewer
    on_loop(viewer, lambda: viewer.displays_panel.add("Marker", name="Text", values={"Topic": "/text"}))  # fmt: skip
    wait_for(lambda: "messages received" in _statuses(viewer).get("Text", ""), what="text status")

    def ink_seen(camera: Any, wide_ratio: float = 0.0) -> tuple[int, int, float]:
        """The green text's ink (height, width [px]) and line height [px], once drawn (and at
        least ``wide_ratio`` line heights wide: turned to a new camera takes a round trip)."""
        canvas = page.locator("canvas").first.bounding_box()
        found: list[tuple[int, int, float]] = []

        def seen() -> bool:
            found[:] = [_text_ink(screenshot(page), camera, canvas, published.GREEN_TEXT_XYZ)]
            height, width, line = found[0]
            return height > 0.4 * line and width > wide_ratio * line

        wait_for(seen, what=f"green text at {published.GREEN_TEXT_XYZ} ({found})")
        return found[0]

    camera = _look_at_origin(viewer, (0.0, -6.0, 1.0))
    height_px, width_px, line_px = ink_seen(camera)
    shot = screenshot(page)
    save_shot(page, "marker_text_front")
    # An "H" is the font's cap height: below the line height scale.z, above half of it.
    assert 0.5 * line_px < height_px < line_px, (height_px, line_px)
    assert width_px > 0.5 * line_px  # "HH" read face-on
    # Half-transparent red over the page's light background: red, lighter than pure red.
    canvas = page.locator("canvas").first.bounding_box()
    (red_uv,) = _project(camera, canvas, np.array([published.RED_TEXT_XYZ]))

    def half_red() -> bool:
        patch = screenshot(page)[_box(red_uv, line_px)].astype(int)
        blended = (patch[..., 0] > 200) & (patch[..., 1] < 190) & (patch[..., 1] > 60)
        return bool(blended.sum() > 10 and not _pure(patch, (255, 0, 0)).any())

    wait_for(half_red, what=f"half-transparent red text at {red_uv}")
    assert not (
        shot[_box(red_uv, 3 * line_px)].max(axis=2) < 60
    ).any()  # no black text (viser's labels)

    # From the side the text still faces the camera: as wide as before, for its distance
    # (text fixed in one plane would be seen edge-on).
    camera = _look_at_origin(viewer, (-6.0, 0.0, 1.0))
    # (text fixed in one plane would be seen edge-on: it would never get as wide)
    side_height_px, _, side_line_px = ink_seen(camera, 0.8 * width_px / line_px)
    save_shot(page, "marker_text_side")
    assert side_height_px < side_line_px


def test_a_mesh_resource_marker_shows_its_texture_tinted_or_the_marker_colour(
    marker_viewer: tuple[Viewer, Any],
) -> None:
    viewer, page = marker_viewer
    on_loop(viewer, lambda: viewer.displays_panel.add("MarkerArray", name="Meshes", values={"Topic": "/meshes"}))  # fmt: skip
    camera = _look_at_origin(viewer, (0.0, -6.0, 0.0))
    canvas = page.locator("canvas").first.bounding_box()
    half = 0.2 * published.MESH_SCALE  # the cube's half width [m]
    # the textured cube's face towards the camera: a 2 x 2 checker, red at top left
    x0, _, z0 = published.TEXTURED_XYZ
    quadrants = np.array([(x0 + sx * half / 2, -half, z0 + sz * half / 2)
                          for sx, sz in ((-1, 1), (1, 1), (-1, -1), (1, -1))])  # fmt: skip
    yellow = np.array([published.YELLOW_XYZ]) + np.array([0.0, -half, 0.0])
    # the blue-tinted copy: RViz 2's tint pass (alpha min(1, 0.5)) over red is (0.5, 0, 0.5)
    x1, _, z1 = published.TINTED_XYZ
    tinted = np.array([(x1 + sx * half / 2, -half, z1 + sz * half / 2) for sx, sz in ((-1, 1), (1, 1))])  # fmt: skip

    def hue(patch: np.ndarray) -> str:
        r, g, b = (float(np.median(patch[..., k])) for k in range(3))
        if r > 80 and g > 80 and b < 0.5 * min(r, g):
            return "yellow"
        if r > 50 and b > 50 and g < 0.3 * min(r, b) and 0.6 < r / b < 1.6:
            return "purple"
        if r > 60 and r > 2 * max(g, b):
            return "red"
        if b > 60 and b > 2 * max(r, g):
            return "blue"
        return "other"

    seen: list[list[str]] = []

    def drawn() -> bool:
        shot = screenshot(page)
        points = _project(camera, canvas, np.vstack([quadrants, yellow, tinted]))
        seen[:] = [[hue(shot[_box(uv, 4)]) for uv in points]]
        return seen[0] == ["red", "blue", "blue", "red", "yellow", "purple", "blue"]

    wait_for(drawn, what=f"the checker, the yellow cube and the tinted checker (seen {seen})")
    save_shot(page, "marker_mesh_texture")
    assert _statuses(viewer)["Meshes"].endswith("messages received")


def test_pose_with_covariance_draws_the_position_ellipsoid_and_orientation_discs(
    marker_viewer: tuple[Viewer, Any],
) -> None:
    """RGB colour style: the roll disc (1.6 m along x) red, pitch (y) green, yaw (z) blue;
    the position ellipsoid (1 m along x) purple; Orientation off hides the discs."""
    viewer, page = marker_viewer
    values = {"Topic": "/pose_cov", "Covariance/Position/Alpha": 1.0,
              "Covariance/Orientation/Color Style": "RGB", "Covariance/Orientation/Alpha": 1.0,
              "Covariance/Orientation/Offset": 1.6}  # fmt: skip
    on_loop(viewer, lambda: viewer.displays_panel.add("PoseWithCovariance", name="Cov", values=values))  # fmt: skip
    wait_for(lambda: "messages received" in _statuses(viewer).get("Cov", ""), what="status")
    camera = _look_at_origin(viewer, (6.0, -6.0, 4.0))
    canvas = page.locator("canvas").first.bounding_box()
    where = _project(camera, canvas, np.array([(1.6, 0, 0), (0, 1.6, 0), (0, 0, 1.6), (-0.6, 0, 0)]))  # fmt: skip

    def hue(shot: np.ndarray, uv: np.ndarray) -> str:
        r, g, b = (float(np.median(shot[_box(uv, 2)][..., k])) for k in range(3))
        if r > 100 and b > 100 and g < 0.6 * min(r, b):
            return "purple"
        for name, (c, others) in {"red": (r, (g, b)), "green": (g, (r, b)), "blue": (b, (r, g))}.items():  # fmt: skip
            if c > 60 and c > 1.8 * max(others):
                return name
        return "other"

    seen: list[list[str]] = []

    def shown(expected: list[str]) -> bool:
        shot = screenshot(page)
        seen[:] = [[hue(shot, uv) for uv in where]]
        return seen[0] == expected

    try:
        wait_for(lambda: shown(["red", "green", "blue", "purple"]), what="discs and ellipsoid")
    finally:
        save_shot(page, "pose_covariance")
        print("seen", seen, "at", where.round().tolist())
    on_loop(viewer, lambda: viewer.displays.displays[-1].set_option("Covariance/Orientation/Value", False))  # fmt: skip
    wait_for(lambda: shown(["other", "other", "other", "purple"]), what=f"discs hidden ({seen})")
