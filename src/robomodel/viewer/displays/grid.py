"""RViz's Grid display: a grid of lines in a plane of its reference frame.

Options and defaults are rviz_default_plugins' ``GridDisplay``
(ros2/rviz f7112b1ae4337363c4d8177bffe7cce6bbcabf29,
rviz_default_plugins/src/rviz_default_plugins/displays/grid/grid_display.cpp); the lines are
rviz_rendering's ``Grid::createLines`` (rviz_rendering/src/rviz_rendering/objects/grid.cpp):
``Plane Cell Count`` cells of ``Cell Size`` each way, centred on the frame's origin, repeated
``Normal Cell Count`` times along the normal with lines joining the planes.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from robomodel.viewer._poses import wxyz_xyz_from_matrix
from robomodel.viewer.displays.base import (
    Display,
    DisplayStatus,
    FrameLookup,
    Option,
    OptionKind,
    color_rgb,
    register_display,
)

__all__ = ["PLANES", "GridDisplay", "grid_segments"]

_FIXED = "<Fixed Frame>"  # RViz's TfFrameProperty: the fixed frame, whichever it is

# Columns: where rviz_rendering's grid axes (in-plane a, normal, in-plane b) go in the
# reference frame. XY and XZ are GridDisplay::updatePlane's orientations; YZ is the plane
# through y and z (normal x), what the option names.
PLANES: dict[str, NDArray[np.float64]] = {
    "XY": np.array([[1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, -1.0, 0.0]]),
    "XZ": np.eye(3),
    "YZ": np.array([[0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]),
}


def grid_segments(
    cell_count: int,
    cell_size_m: float,
    *,
    normal_count: int = 0,
    plane: str = "XY",
    offset_m: tuple[float, float, float] = (0.0, 0.0, 0.0),
) -> NDArray[np.float64]:
    """The grid's lines in its reference frame, shape (n, 2, 3) [m].

    Args:
        cell_count: Cells along each in-plane axis (RViz's "Plane Cell Count", >= 1).
        cell_size_m: A cell's side [m] ("Cell Size").
        normal_count: Cells along the normal ("Normal Cell Count"; > 0 makes it 3D).
        plane: "XY", "XZ" or "YZ".
        offset_m: The grid centre in the reference frame [m] ("Offset").

    Raises:
        KeyError: An unknown plane.
    """
    rotation = PLANES[plane]
    extent = cell_size_m * cell_count / 2.0
    steps = extent - cell_size_m * np.arange(cell_count + 1)
    lines: list[tuple[tuple[float, float, float], tuple[float, float, float]]] = []
    for level in range(normal_count + 1):
        h = (normal_count / 2.0 - level) * cell_size_m
        for s in steps:
            lines.append(((s, h, -extent), (s, h, extent)))
            lines.append(((-extent, h, s), (extent, h, s)))
    if normal_count > 0:
        top = normal_count / 2.0 * cell_size_m
        lines += [((a, -top, b), (a, top, b)) for a in steps for b in steps]
    local = np.asarray(lines, dtype=np.float64)
    world: NDArray[np.float64] = local @ rotation.T + np.asarray(offset_m, dtype=np.float64)
    return world


@register_display
class GridDisplay(Display):
    """RViz's Grid display (defaults: 10 cells of 1 m in XY, gray at alpha 0.5)."""

    class_name = "Grid"
    options = (
        Option("Reference Frame", _FIXED, OptionKind.TEXT, help="The TF frame of its origin"),
        Option("Plane Cell Count", 10, OptionKind.INT, minimum=1, help="Cells in the plane"),
        Option("Normal Cell Count", 0, OptionKind.INT, minimum=0, help="Cells along the normal"),
        Option("Cell Size", 1.0, OptionKind.FLOAT, minimum=0.0001, help="A cell's side [m]"),
        Option("Line Style/Value", "Lines", OptionKind.CHOICE, choices=("Lines", "Billboards")),
        Option("Line Style/Line Width", 0.03, OptionKind.FLOAT, minimum=0.001, help="[m]"),
        Option("Color", "160; 160; 164", OptionKind.COLOR, help="The color of the grid lines"),
        Option("Alpha", 0.5, OptionKind.FLOAT, minimum=0.0, maximum=1.0),
        Option("Plane", "XY", OptionKind.CHOICE, choices=tuple(PLANES)),
        Option("Offset/X", 0.0, OptionKind.FLOAT, help="[m] in the reference frame"),
        Option("Offset/Y", 0.0, OptionKind.FLOAT),
        Option("Offset/Z", 0.0, OptionKind.FLOAT),
    )

    def segments(self) -> NDArray[np.float64]:
        """The lines of the current options, in the reference frame [m]."""
        return grid_segments(
            int(self.option("Plane Cell Count")),
            float(self.option("Cell Size")),
            normal_count=int(self.option("Normal Cell Count")),
            plane=str(self.option("Plane")),
            offset_m=(
                float(self.option("Offset/X")),
                float(self.option("Offset/Y")),
                float(self.option("Offset/Z")),
            ),
        )

    def draw(self, lookup: FrameLookup) -> DisplayStatus:
        frame = str(self.option("Reference Frame")).strip()
        if frame in ("", _FIXED):
            frame = self.context.fixed_frame()
        placement = lookup(frame, 0)
        node = self.node("lines")
        if placement.T_fixed_frame is None:
            if node is not None:
                node.visible = False
            return DisplayStatus.error(placement.reason)
        if node is None:
            node = self._add_lines()
        node.wxyz, node.position = wxyz_xyz_from_matrix(placement.T_fixed_frame)
        node.visible = True
        return DisplayStatus.ok(f"Transform OK: {frame}")

    def _add_lines(self) -> object:
        # RViz blends the color with Alpha; viser's lines are opaque, so it is mixed with the
        # page's white background instead (a 0.5 gray grid reads as lighter, as in RViz).
        alpha = float(self.option("Alpha"))
        rgb = color_rgb(str(self.option("Color")))
        mixed = tuple(round(float(c) * alpha + 255.0 * (1.0 - alpha)) for c in rgb)
        billboards = self.option("Line Style/Value") == "Billboards"
        return self.add_node(
            "lines",
            "line_segments",
            points=self.segments().astype(np.float32),
            colors=mixed,
            thickness=float(self.option("Line Style/Line Width")) if billboards else 1.0,
            thickness_units="world" if billboards else "screen",
        )
