"""RViz's Axes display: x (red), y (green), z (blue) axes of one frame in the fixed frame."""

from __future__ import annotations

from robomodel.viewer._poses import wxyz_xyz_from_matrix
from robomodel.viewer.displays.base import (
    Display,
    DisplayStatus,
    FrameLookup,
    Option,
    OptionKind,
    register_display,
)

__all__ = ["AxesDisplay"]

_FIXED = "<Fixed Frame>"  # RViz's TfFrameProperty: the fixed frame, whichever it is


@register_display
class AxesDisplay(Display):
    """RViz's Axes display (rviz default_plugins/displays/axes; defaults Length 1, Radius 0.1)."""

    class_name = "Axes"
    options = (
        Option("Reference Frame", _FIXED, OptionKind.TEXT, help="The frame the axes show"),
        Option("Length", 1.0, OptionKind.FLOAT, minimum=0.0001, help="Axis length [m]"),
        Option("Radius", 0.1, OptionKind.FLOAT, minimum=0.0001, help="Axis radius [m]"),
    )

    def draw(self, lookup: FrameLookup) -> DisplayStatus:
        frame = str(self.option("Reference Frame")).strip()
        if frame in ("", _FIXED):
            frame = self.context.fixed_frame()
        placement = lookup(frame, 0)
        if placement.T_fixed_frame is None:
            node = self.node("axes")
            if node is not None:
                node.visible = False
            return DisplayStatus.error(placement.reason)
        wxyz, xyz = wxyz_xyz_from_matrix(placement.T_fixed_frame)
        node = self.node("axes")
        if node is None:
            node = self.add_node(
                "axes",
                "frame",
                axes_length=float(self.option("Length")),
                axes_radius=float(self.option("Radius")),
                origin_radius=float(self.option("Radius")),
            )
        node.wxyz, node.position, node.visible = wxyz, xyz, True
        return DisplayStatus.ok(f"Transform OK: {frame}")
