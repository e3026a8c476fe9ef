"""RViz's covariance visual (covariance_visual.cpp): the orientation covariance's discs and the
2D yaw triangle, their sizes from the variances, Scale, Offset, Frame and Color Style, on
PoseWithCovariance and Odometry (a fake scene)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from robomodel.viewer.displays.covariance import covariance_shapes
from tests.viewer.test_pose_displays import Odometry, PoseWithCovarianceStamped, at, start

SIGMA_RPY = (0.2, 0.3, 0.4)  # [rad]


def covariance(position_var: tuple[float, float, float] = (1.0, 0.25, 0.0625), sigma_rpy: tuple[float, float, float] = SIGMA_RPY) -> np.ndarray:  # fmt: skip
    return np.diag([*position_var, *(s * s for s in sigma_rpy)])


def half_extents(vertices: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Centre and half extents of a shape's bounding box."""
    lo, hi = vertices.min(axis=0), vertices.max(axis=0)
    return (lo + hi) / 2, (hi - lo) / 2


def test_each_axis_disc_subtends_the_other_two_axes_standard_deviations() -> None:
    """At the tip of x: pitch (along z) and yaw (along y); of y: roll (z) and yaw (x); of z:
    roll (x) and pitch (y). A disc Offset away is tan(Scale * sigma) * Offset across (half)."""
    r, p, y = SIGMA_RPY
    for offset, scale in ((1.0, 1.0), (2.0, 1.5)):
        shapes = covariance_shapes(covariance(), orientation_offset=offset, orientation_scale=scale)
        assert shapes is not None and not shapes.is_2d
        expected = {  # axis -> half extents (x, y, z) / offset
            0: (None, math.tan(scale * y), math.tan(scale * p)),
            1: (math.tan(scale * y), None, math.tan(scale * r)),
            2: (math.tan(scale * r), math.tan(scale * p), None),
        }
        for axis, (vertices, _faces) in enumerate(shapes.orientation):
            centre, half = half_extents(vertices)
            np.testing.assert_allclose(centre, offset * np.eye(3)[axis], atol=1e-6)
            for k, want in enumerate(expected[axis]):
                if want is None:  # the disc's thickness along its axis: 1 mm
                    assert half[k] == pytest.approx(0.0005, abs=1e-6)
                else:
                    assert half[k] == pytest.approx(offset * want, rel=2e-3)


def test_a_wide_angle_is_bounded_at_89_degrees() -> None:
    shapes = covariance_shapes(covariance(sigma_rpy=(3.0, 3.0, 3.0)))
    assert shapes is not None
    _centre, half = half_extents(shapes.orientation[2][0])
    assert half[0] == pytest.approx(math.tan(math.radians(89)), rel=2e-3)


def test_a_correlated_block_turns_the_disc_to_its_eigenvectors() -> None:
    """Yaw disc (z tip): the roll/pitch block's eigenvector (a, b) lies along (a, -b) in the
    pose's (x, y) (the yaw offset node's Rx(90) takes the disc's z to -y)."""
    c = covariance()
    c[3, 3], c[4, 4] = 0.05, 0.05
    c[3, 4] = c[4, 3] = 0.04
    shapes = covariance_shapes(c)
    assert shapes is not None
    vertices = shapes.orientation[2][0][:, :2].astype(float)
    values, vectors = np.linalg.eigh([[0.05, 0.04], [0.04, 0.05]])
    for value, (a, b) in zip(values, vectors.T, strict=True):
        reach = float((vertices @ np.array([a, -b])).max())
        assert reach == pytest.approx(math.tan(math.sqrt(value)), rel=2e-2)


def test_a_2d_pose_gets_a_flat_ellipse_and_a_yaw_triangle() -> None:
    c = np.zeros((6, 6))
    c[0, 0], c[1, 1], c[5, 5] = 0.25, 1.0, 0.09
    shapes = covariance_shapes(c, orientation_offset=2.0)
    assert shapes is not None and shapes.is_2d and len(shapes.orientation) == 1
    assert sorted(shapes.radii_m) == pytest.approx([0.0005, 0.5, 1.0])
    vertices = shapes.orientation[0][0]
    np.testing.assert_allclose(vertices.min(axis=0), [0.0, -2 * math.tan(0.3), -0.0005], atol=1e-4)
    np.testing.assert_allclose(vertices.max(axis=0), [2.0, 2 * math.tan(0.3), 0.0005], atol=1e-4)


def test_nan_is_not_drawn() -> None:
    c = covariance()
    c[0, 1] = math.nan
    assert covariance_shapes(c) is None


def _pose_with_covariance(yaw: float) -> object:
    msg = PoseWithCovarianceStamped()
    msg.header.frame_id = "odom"
    msg.pose.pose = at(1.0, 2.0, yaw)
    msg.pose.covariance = list(covariance().ravel())
    return msg


def _world_vertices(node: object) -> np.ndarray:
    w, x, y, z = node.kwargs["wxyz"]
    R = Rotation.from_quat([x, y, z, w]).as_matrix()
    return node.kwargs["vertices"] @ R.T + np.asarray(node.kwargs["position"])


def test_pose_with_covariance_draws_the_orientation_discs_local_or_fixed() -> None:
    display, scene = start("PoseWithCovariance")
    display.receive(_pose_with_covariance(math.pi / 2))
    lookup = lookup_from_shift(1.0)
    display.draw(lookup)
    discs = [scene.nodes[f"/displays/d/covariance_orientation{i}"] for i in range(3)]
    assert all(d.kwargs["color"] == (255, 255, 127) and d.kwargs["opacity"] == 0.5 for d in discs)
    # Local: the roll disc sits 1 m along the pose's x, which the yaw turned to the map's +y
    centre, _ = half_extents(_world_vertices(discs[0]))
    np.testing.assert_allclose(centre, (2.0, 3.0, 0.0), atol=1e-6)
    display.set_option("Covariance/Orientation/Frame", "Fixed")
    display.set_option("Covariance/Orientation/Color Style", "RGB")
    display.draw(lookup)
    discs = [scene.nodes[f"/displays/d/covariance_orientation{i}"] for i in range(3)]
    assert [d.kwargs["color"] for d in discs] == [(255, 0, 0), (0, 255, 0), (0, 0, 255)]
    centre, _ = half_extents(_world_vertices(discs[0]))  # Fixed: along the frame's +x
    np.testing.assert_allclose(centre, (3.0, 2.0, 0.0), atol=1e-6)
    display.set_option("Covariance/Orientation/Value", False)
    display.draw(lookup)
    assert "/displays/d/covariance" in scene.nodes
    assert not any(f"/displays/d/covariance_orientation{i}" in scene.nodes for i in range(3))


def lookup_from_shift(x: float) -> object:
    from tests.viewer.fake_scene import lookup_from
    from tests.viewer.test_pose_displays import shifted

    return lookup_from({"odom": shifted(x)})


def test_odometry_draws_and_forgets_each_kept_pose_s_covariance() -> None:
    display, scene = start("Odometry", Keep=1)
    for x in (0.0, 1.0):
        msg = Odometry()
        msg.header.frame_id = "odom"
        msg.pose.pose = at(x)
        msg.pose.covariance = list(covariance().ravel())
        display.receive(msg)
        display.draw(lookup_from_shift(0.0))
    discs = sorted(n for n in scene.nodes if "_orientation" in n)
    assert len(discs) == 3  # Keep 1: the first pose's discs are gone
    centre, _ = half_extents(_world_vertices(scene.nodes[discs[0]]))
    np.testing.assert_allclose(centre, (2.0, 0.0, 0.0), atol=1e-6)
