"""The TF display's axis cylinders: closed, wound outwards, along their axis from the origin,
the same solid as trimesh's cylinder of the same sections."""

from __future__ import annotations

import numpy as np
import pytest
import trimesh

from robomodel.viewer.tf_display import _axis_mesh


@pytest.mark.parametrize("axis", [0, 1, 2])
def test_axis_cylinder_is_trimesh_s_cylinder_from_the_origin_along_its_axis(axis: int) -> None:
    length_m, radius_m = 0.1, 0.004
    vertices, faces = _axis_mesh(axis, length_m, radius_m)
    ours = trimesh.Trimesh(vertices, faces, process=False)
    reference = trimesh.creation.cylinder(radius=radius_m, height=length_m, sections=12)
    assert ours.is_watertight and ours.is_winding_consistent
    assert ours.volume > 0  # wound outwards
    assert ours.volume == pytest.approx(reference.volume, rel=1e-9)
    assert ours.area == pytest.approx(reference.area, rel=1e-9)
    low, high = ours.bounds
    assert low[axis] == pytest.approx(0.0) and high[axis] == pytest.approx(length_m)
    across = [k for k in range(3) if k != axis]
    np.testing.assert_allclose(np.linalg.norm(vertices[:, across], axis=1).max(), radius_m)
