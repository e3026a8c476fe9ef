"""RViz's Grid display: its lines (cell count, size, plane, offset), placement through TF and
its option table against RViz's default configs."""

from __future__ import annotations

import numpy as np
import pytest

from robomodel.viewer.displays.base import display_class
from robomodel.viewer.displays.grid import GridDisplay, grid_segments
from robomodel.viewer.displays.rviz_io import display_entry, display_values
from robomodel.viewer.rviz_document import default_rviz_config
from robomodel.viewer.rviz_model import RvizDialect
from tests.viewer.fake_scene import FakeScene, fake_context, lookup_from


def _lines(segments: np.ndarray) -> set[tuple[float, ...]]:
    """Segments as a set of rounded, direction-free endpoint pairs."""
    out = set()
    for a, b in np.round(segments, 9) + 0.0:
        out.add(tuple(min(tuple(a), tuple(b))) + tuple(max(tuple(a), tuple(b))))
    return out


def test_the_default_grid_is_11_lines_each_way_over_10_m_in_xy() -> None:
    segments = grid_segments(10, 1.0)
    assert segments.shape == (22, 2, 3)
    assert np.all(segments[:, :, 2] == 0.0)  # in the XY plane
    assert segments[:, :, :2].min() == -5.0 and segments[:, :, :2].max() == 5.0
    along_x = {(-5.0, y, 0.0, 5.0, y, 0.0) for y in range(-5, 6)}
    along_y = {(x, -5.0, 0.0, x, 5.0, 0.0) for x in range(-5, 6)}
    assert _lines(segments) == {tuple(float(v) for v in s) for s in along_x | along_y}


def test_cell_count_and_size_set_the_extent_and_spacing() -> None:
    segments = grid_segments(4, 0.5)
    assert segments.shape == (10, 2, 3)
    xs = sorted({float(v) for v in np.round(segments[:, :, 0].ravel(), 9)})
    assert xs == [-1.0, -0.5, 0.0, 0.5, 1.0]
    assert grid_segments(3, 1.0).shape == (8, 2, 3)
    assert sorted({float(v) for v in grid_segments(3, 1.0)[:, :, 1].ravel()}) == [-1.5, -0.5, 0.5, 1.5]  # fmt: skip


@pytest.mark.parametrize(("plane", "flat_axis"), [("XY", 2), ("XZ", 1), ("YZ", 0)])
def test_each_plane_keeps_one_axis_flat(plane: str, flat_axis: int) -> None:
    segments = grid_segments(2, 1.0, plane=plane)
    assert np.all(segments[:, :, flat_axis] == 0.0)
    for axis in {0, 1, 2} - {flat_axis}:
        assert segments[:, :, axis].min() == -1.0 and segments[:, :, axis].max() == 1.0


def test_offset_moves_every_line_and_normal_cells_make_it_3d() -> None:
    moved = grid_segments(2, 1.0, offset_m=(1.0, -2.0, 0.5))
    np.testing.assert_allclose(moved, grid_segments(2, 1.0) + np.array([1.0, -2.0, 0.5]))
    cube = grid_segments(2, 1.0, normal_count=2)
    # 3 planes of 6 lines, plus 3 x 3 lines joining them along z
    assert cube.shape == (3 * 6 + 9, 2, 3)
    assert sorted({float(v) for v in cube[:, :, 2].ravel()}) == [-1.0, 0.0, 1.0]
    vertical = cube[np.abs(cube[:, 0, 2] - cube[:, 1, 2]) > 0]
    assert len(vertical) == 9 and np.all(np.abs(vertical[:, :, 2]) == 1.0)


def test_an_unknown_plane_is_refused() -> None:
    with pytest.raises(KeyError):
        grid_segments(10, 1.0, plane="XX")


def test_the_display_draws_in_its_reference_frame() -> None:
    scene = FakeScene()
    display = GridDisplay(
        "Grid", fake_context(scene), {"Reference Frame": "base_link", "Plane Cell Count": 4}
    )
    T = np.eye(4)
    T[:3, 3] = (1.0, 2.0, 3.0)
    status = display.draw(lookup_from({"map": np.eye(4), "base_link": T}))
    assert status.text == "Transform OK: base_link"
    node = scene.nodes["/displays/Grid/lines"]
    assert node.kind == "line_segments" and node.kwargs["points"].shape == (10, 2, 3)
    np.testing.assert_allclose(node.position, (1.0, 2.0, 3.0))
    # RViz's gray 160;160;164 at alpha 0.5 over white
    assert node.kwargs["colors"] == (208, 208, 210)
    missing = display.draw(lookup_from({"map": np.eye(4)}))
    assert missing.text == "No transform from [base_link] to [map]" and not node.visible


def test_billboards_draw_lines_of_line_width_in_metres() -> None:
    scene = FakeScene()
    display = GridDisplay("Grid", fake_context(scene), {"Line Style/Value": "Billboards"})
    display.draw(lookup_from({"map": np.eye(4)}))
    node = scene.nodes["/displays/Grid/lines"]
    assert node.kwargs["thickness"] == pytest.approx(0.03)
    assert node.kwargs["thickness_units"] == "world"


@pytest.mark.parametrize("dialect", [RvizDialect.ROS1, RvizDialect.ROS2])
def test_the_option_table_reads_and_writes_rvizs_default_grid(dialect: RvizDialect) -> None:
    assert display_class("Grid") is GridDisplay
    (entry,) = [d for d in default_rviz_config(dialect).displays if d.name == "Grid"]
    values, skipped = display_values(GridDisplay, entry.settings, dialect)
    assert skipped == []
    display = GridDisplay("Grid", fake_context(FakeScene()), values)
    assert display.values == GridDisplay("Grid", fake_context(FakeScene())).values
    # unchanged: the entry as read; a new display: every property RViz writes, same values
    assert display_entry(display, dialect, entry) == entry
    fresh = display_entry(display, dialect)
    assert fresh.class_name == entry.class_name
    assert dict(fresh.settings) == {k: v for k, v in entry.settings.items() if k != "Value"}
