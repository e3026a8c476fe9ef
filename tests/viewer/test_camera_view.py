"""The Camera display's "View through the camera" without a browser: the page camera's pose
and field of view from TF and CameraInfo, the pages' cameras kept and given back, and the
image quads on a fake scene."""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from robomodel.runtime.msg import get_message_type
from robomodel.viewer.displays import display_class
from robomodel.viewer.displays.camera_view import CameraView, PageCameras, camera_view
from tests.viewer.fake_scene import FakeScene, fake_context, lookup_from
from tests.viewer.test_sensor_displays import checkerboard

CameraInfo = get_message_type("sensor_msgs/msg/CameraInfo")


def _info(width: int = 640, height: int = 480, fx: float = 500.0, fy: float = 400.0) -> object:
    info = CameraInfo(height=height, width=width)
    info.p = [fx, 0.0, width / 2, 0.0, 0.0, fy, height / 2, 0.0, 0.0, 0.0, 1.0, 0.0]
    return info


def _pose() -> np.ndarray:
    T = np.eye(4)
    T[:3, :3] = Rotation.from_euler("zx", [30, -100], degrees=True).as_matrix()
    T[:3, 3] = (1.0, 2.0, 3.0)
    return T


def _page_pixel(view: CameraView, height_px: float, p_fixed: np.ndarray) -> tuple[float, float]:
    """Where a page of ``height_px`` showing ``view`` draws a point (viser's OpenCV camera,
    offsets from the page's centre)."""
    w, x, y, z = view.wxyz
    p = Rotation.from_quat([x, y, z, w]).as_matrix().T @ (p_fixed - np.array(view.position))
    f = (height_px / 2) / math.tan(view.fov_rad / 2)
    return f * p[0] / p[2], f * p[1] / p[2]


@pytest.mark.parametrize("zoom", [1.0, 2.0])
def test_camera_view_puts_the_image_edges_at_the_page_edges(zoom: float) -> None:
    T, info = _pose(), _info()
    view = camera_view(T, info, zoom)
    assert view is not None
    np.testing.assert_allclose(view.position, (1.0, 2.0, 3.0))
    w, x, y, z = view.wxyz
    np.testing.assert_allclose(Rotation.from_quat([x, y, z, w]).as_matrix(), T[:3, :3], atol=1e-9)
    np.testing.assert_allclose(np.subtract(view.look_at, view.position), T[:3, 2], atol=1e-9)
    assert view.fov_rad == pytest.approx(2 * math.atan(480 / (2 * 400.0 * zoom)))
    assert view.size_per_m == pytest.approx((640 / (500.0 * zoom), 480 / (400.0 * zoom)))
    # the pinhole model's top-left image corner, 2 m ahead, on a page 480 px high
    corner_optical = np.array([-320 / (500.0 * zoom), -240 / (400.0 * zoom), 1.0]) * 2.0
    u, v = _page_pixel(view, 480.0, (T @ np.append(corner_optical, 1.0))[:3])
    assert v == pytest.approx(-240.0) and u == pytest.approx(-240.0 * (640 / 500) / (480 / 400))


def test_camera_view_unusable_camera_info() -> None:
    assert camera_view(_pose(), _info(width=0)) is None
    assert camera_view(_pose(), _info(fy=0.0)) is None


class _Camera(SimpleNamespace):
    update_timestamp = 1.0


def _client(client_id: int) -> SimpleNamespace:
    camera = _Camera(position=np.array([0.0, -6.0, 8.0]), look_at=np.zeros(3), fov=1.0,
                     up_direction=np.array([0.0, 0.0, 1.0]), wxyz=np.array([1.0, 0, 0, 0]))  # fmt: skip
    return SimpleNamespace(client_id=client_id, camera=camera)


def test_page_cameras_follow_undo_a_drag_and_give_the_camera_back() -> None:
    client = _client(7)
    pages = PageCameras(lambda: (client,))
    view = camera_view(_pose(), _info())
    assert view is not None
    pages.follow(view)
    assert np.allclose(client.camera.position, view.position) and client.camera.fov == view.fov_rad
    client.camera.position = np.array([5.0, 5.0, 5.0])  # the user drags
    pages.follow(view)
    assert np.allclose(client.camera.position, view.position)
    pages.release()
    assert np.allclose(client.camera.position, (0.0, -6.0, 8.0)) and client.camera.fov == 1.0
    assert np.allclose(client.camera.look_at, 0.0) and not pages.following


def test_camera_display_view_through_draws_quads_and_hides_the_frustum() -> None:
    scene, client = FakeScene(), _client(1)
    context = fake_context(scene)
    context.clients = lambda: (client,)
    values = {"Topic": "/camera/image_raw", "Overlay Alpha": 0.25}
    display = display_class("Camera")("cam", context, values)
    display.receive(checkerboard())
    display.subscriptions()[1].callback(_info(4, 4, 2.0, 2.0))
    lookup = lookup_from({"camera_optical": _pose()})
    assert display.draw(lookup).level.value == "warn"
    display.set_view_through(True)
    status = display.draw(lookup)
    assert status.level.value == "ok" and "looks through the camera" in status.text
    nodes = scene.visible("/displays/cam")
    assert sorted(n.rsplit("/", 1)[1] for n in nodes) == ["background", "overlay"]
    overlay = nodes["/displays/cam/overlay"].kwargs["image"]
    assert overlay.shape == (4, 4, 4) and (overlay[..., 3] == round(0.25 * 255)).all()
    assert np.allclose(client.camera.position, (1.0, 2.0, 3.0))
    display.set_option("Image Rendering", "background")
    display.draw(lookup)
    assert sorted(scene.visible("/displays/cam")) == ["/displays/cam/background"]
    display.set_view_through(False)
    assert display.draw(lookup).level.value == "warn"
    assert [n.kind for n in scene.visible("/displays/cam").values()] == ["camera_frustum"]
    assert np.allclose(client.camera.position, (0.0, -6.0, 8.0))
