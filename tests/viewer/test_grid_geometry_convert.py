"""OccupancyGrid -> RGBA (displays.occupancy) and the pose-like displays' geometry (displays.geometry)
against RViz's palettes and shapes."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from robomodel.runtime.msg import deserialize, get_message_type, serialize
from robomodel.viewer.displays.geometry import (
    ArrowTrail,
    arrow_segments,
    covariance_ellipsoid,
    flat_arrow_segments,
    matrix_from_xyz_xyzw,
    pose_matrices,
    quaternion_angular_distance,
    wrench_shapes,
)
from robomodel.viewer.displays.image import nearest_upscale
from robomodel.viewer.displays.occupancy import (
    GridError,
    grid_rgba,
    grid_texture_pose,
    map_palette,
)

OccupancyGrid = get_message_type("nav_msgs/msg/OccupancyGrid")


def make_grid(cells: list[list[int]], *, resolution=0.5, origin=(1.0, 2.0, 0.0), yaw=0.0):
    h, w = len(cells), len(cells[0])
    msg = OccupancyGrid()
    msg.header.frame_id = "map"
    msg.info.resolution = resolution
    msg.info.width, msg.info.height = w, h
    msg.info.origin.position.x, msg.info.origin.position.y, msg.info.origin.position.z = origin
    msg.info.origin.orientation.z, msg.info.origin.orientation.w = math.sin(yaw / 2), math.cos(yaw / 2)  # fmt: skip
    msg.data = [v for row in cells for v in row]
    return deserialize(serialize(msg), OccupancyGrid)


UNKNOWN = (0x70, 0x89, 0x86)


def test_map_scheme_free_occupied_unknown_cells_and_row_order() -> None:
    # row 0 is y = 0 (the map's bottom): free, occupied; row 1: unknown, half
    rgba = grid_rgba(make_grid([[0, 100], [-1, 50]]), alpha=1.0)
    assert rgba.shape == (2, 2, 4)
    np.testing.assert_array_equal(rgba[0, 0], (255, 255, 255, 255))  # free, (x0, y0)
    np.testing.assert_array_equal(rgba[0, 1], (0, 0, 0, 255))  # occupied
    np.testing.assert_array_equal(rgba[1, 0], (*UNKNOWN, 255))  # unknown
    np.testing.assert_array_equal(rgba[1, 1], (128, 128, 128, 255))  # 255 - 255*50/100
    big = nearest_upscale(rgba)
    assert big.shape == (256, 256, 4)
    np.testing.assert_array_equal(big[127, 128], rgba[0, 1])
    np.testing.assert_array_equal(big[128, 127], rgba[1, 0])
    assert grid_rgba(make_grid([[0]]))[0, 0, 3] == int(255 * 0.7)  # RViz's Alpha default


def test_palettes_match_rviz_palette_builder() -> None:
    p = map_palette("map")
    assert tuple(p[101]) == (0, 255, 0, 255) and tuple(p[127]) == (0, 255, 0, 255)
    assert tuple(p[128]) == (255, 0, 0, 255) and tuple(p[254]) == (255, 255, 0, 255)
    assert tuple(p[191]) == (255, (255 * 63) // 126, 0, 255)
    c = map_palette("costmap")
    assert tuple(c[0]) == (0, 0, 0, 0) and tuple(c[99]) == (0, 255, 255, 255)
    assert tuple(c[100]) == (255, 0, 255, 255) and tuple(c[50]) == (127, 0, 128, 255)
    r = map_palette("raw")
    assert tuple(r[200]) == (200, 200, 200, 255) and tuple(r[255]) == (255, 255, 255, 255)
    b = map_palette("map", binary=True, threshold=60)
    assert tuple(b[59]) == (255, 255, 255, 255) and tuple(b[60]) == (0, 0, 0, 255)
    with pytest.raises(GridError, match="valid are: map, costmap, raw"):
        map_palette("heat")


def test_grid_errors_have_rviz_messages() -> None:
    msg = make_grid([[0, 0]])
    msg.info.width = 3
    with pytest.raises(GridError, match="width = 3, height = 1, data size = 2"):
        grid_rgba(msg)
    msg = make_grid([[0]])
    msg.info.width = msg.info.height = 0
    msg.data = []
    with pytest.raises(GridError, match=r"Map is zero-sized \(0x0\)"):
        grid_rgba(msg)
    msg = make_grid([[0]])
    msg.info.resolution = float("nan")
    with pytest.raises(GridError, match="nans or infs"):
        grid_rgba(msg)


def test_grid_texture_centre_follows_origin_pose() -> None:
    T, w, h = grid_texture_pose(make_grid([[0] * 4] * 2, resolution=0.5, origin=(1, 2, 0.1), yaw=math.pi / 2))  # fmt: skip
    assert (w, h) == (2.0, 1.0)
    # centre = origin + R(yaw 90) (1, 0.5): x - 0.5, y + 1
    np.testing.assert_allclose(T[:3, 3], (0.5, 3.0, 0.1), atol=1e-12)
    np.testing.assert_allclose(T[:3, 0], (0, 1, 0), atol=1e-12)


def test_pose_matrices_match_scipy() -> None:
    rng = np.random.default_rng(0)
    q = rng.normal(size=(20, 4))
    T = pose_matrices(rng.normal(size=(20, 3)), q)
    np.testing.assert_allclose(T[:, :3, :3], Rotation.from_quat(q).as_matrix(), atol=1e-12)
    np.testing.assert_array_equal(matrix_from_xyz_xyzw((0, 0, 0), (0, 0, 0, 0)), np.eye(4))


def test_arrows_point_along_pose_x() -> None:
    T = matrix_from_xyz_xyzw((1, 2, 3), (0, 0, math.sin(math.pi / 4), math.cos(math.pi / 4)))
    seg = arrow_segments(T[None], 1.3)
    np.testing.assert_allclose(seg[0], [[1, 2, 3], [1, 3.3, 3]], atol=1e-12)
    flat = flat_arrow_segments(np.eye(4)[None], 0.3)
    np.testing.assert_allclose(flat[:, 1], [[0.3, 0, 0], [0.225, 0.06, 0], [0.225, -0.06, 0]])
    np.testing.assert_allclose(flat[1:, 0], [[0.3, 0, 0], [0.3, 0, 0]])


def test_covariance_ellipsoid_axes_and_handedness() -> None:
    R_true = Rotation.from_euler("z", 30, degrees=True).as_matrix()
    cov = R_true @ np.diag([4.0, 1.0, 0.25]) @ R_true.T
    cov6 = np.zeros((6, 6))
    cov6[:3, :3] = cov
    R, radii = covariance_ellipsoid(cov6.ravel(), scale=2.0)
    np.testing.assert_allclose(R @ np.diag((radii / 2) ** 2) @ R.T, cov, atol=1e-12)
    assert np.linalg.det(R) == pytest.approx(1.0)
    np.testing.assert_allclose(sorted(radii), [1.0, 2.0, 4.0])


def test_wrench_arrows_and_hidden_short_ones() -> None:
    s = wrench_shapes((0, 0, 10), (1, 0, 0), force_scale=0.1, torque_scale=1.0, width=0.5)
    assert s.force is not None and s.torque is not None and s.torque_circle is not None
    np.testing.assert_allclose(s.force[1], (0, 0, 1.3))  # RViz's arrow: 1.3 x length
    np.testing.assert_allclose(s.torque[1], (1.3, 0, 0))
    # the circle lies in the plane at half the torque's length, radius a quarter of it
    np.testing.assert_allclose(s.torque_circle[:, 0], 0.5, atol=1e-12)
    np.testing.assert_allclose(np.linalg.norm(s.torque_circle[:, 1:], axis=1), 0.25)
    small = wrench_shapes((0.1, 0, 0), (0, 0, 0))
    assert small.force is None and small.torque is None


def test_arrow_trail_tolerances_and_keep() -> None:
    trail = ArrowTrail(position_tolerance_m=0.1, angle_tolerance_rad=0.1, keep=3)
    ident = (0.0, 0.0, 0.0, 1.0)
    assert trail.offer((0, 0, 0), ident, np.eye(4))
    assert not trail.offer((0.05, 0, 0), ident, np.eye(4))  # within both tolerances
    yaw = (0.0, 0.0, math.sin(0.1), math.cos(0.1))  # 0.2 rad
    assert quaternion_angular_distance(yaw, ident) == pytest.approx(0.2)
    assert trail.offer((0.05, 0, 0), yaw, np.eye(4))  # turned enough
    for k in range(1, 4):
        T = np.eye(4)
        T[0, 3] = k
        assert trail.offer((k, 0, 0), yaw, T)
    assert len(trail.poses) == 3
    np.testing.assert_array_equal(trail.matrices()[:, 0, 3], [1, 2, 3])
