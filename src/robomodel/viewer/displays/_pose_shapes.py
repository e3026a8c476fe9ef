"""Drawing poses as RViz does (arrows, axes, flat arrows) and covariance ellipsoids, shared by
the Pose, PoseWithCovariance, PoseArray, Odometry and Path displays.

The option tables here are RViz's: pose_display.cpp, pose_with_covariance_display.cpp and
odometry_display.cpp name them "Shape", "Color", "Alpha", "Shaft Length", "Shaft Radius",
"Head Length", "Head Radius", "Axes Length", "Axes Radius" (defaults: red-orange 255; 25; 0,
shaft 1 x 0.05, head 0.3 x 0.1, axes 1 x 0.1); covariance_property.cpp gives "Covariance",
"Position" (colour 204; 51; 204, alpha 0.3, scale 1), saved nested as RViz 2 does
(``Covariance: {Value: true, Position: {Value: true, Color: ...}}``). Alpha is kept for the config; viser's
arrows are opaque.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

from robomodel.viewer._poses import wxyz_from_matrices
from robomodel.viewer.displays.base import Display, Option, OptionKind, color_rgb
from robomodel.viewer.displays.geometry import (  # fmt: skip
    arrow_segments,
    covariance_ellipsoid,
    flat_arrow_segments,
)

__all__ = ["ARROW_OPTIONS", "COVARIANCE_OPTIONS", "draw_covariance", "draw_poses"]

ARROW_OPTIONS = (
    Option("Shape", "Arrow", OptionKind.CHOICE, choices=("Arrow", "Axes")),
    Option("Color", "255; 25; 0", OptionKind.COLOR, help="Color to draw the arrow."),
    Option("Alpha", 1.0, OptionKind.FLOAT, minimum=0.0, maximum=1.0),
    Option("Shaft Length", 1.0, OptionKind.FLOAT, minimum=0.0),
    Option("Shaft Radius", 0.05, OptionKind.FLOAT, minimum=0.0),
    Option("Head Length", 0.3, OptionKind.FLOAT, minimum=0.0),
    Option("Head Radius", 0.1, OptionKind.FLOAT, minimum=0.0),
    Option("Axes Length", 1.0, OptionKind.FLOAT, minimum=0.0),
    Option("Axes Radius", 0.1, OptionKind.FLOAT, minimum=0.0),
)
COVARIANCE_OPTIONS = (
    # RViz 2 saves a property with children as {Value: ..., <child>: ...}
    Option("Covariance/Value", True, OptionKind.BOOL, help="Whether to show the covariances."),
    Option("Covariance/Position/Value", True, OptionKind.BOOL),
    Option("Covariance/Position/Color", "204; 51; 204", OptionKind.COLOR),
    Option("Covariance/Position/Alpha", 0.3, OptionKind.FLOAT, minimum=0.0, maximum=1.0),
    Option("Covariance/Position/Scale", 1.0, OptionKind.FLOAT, minimum=0.0),
)


def draw_poses(display: Display, key: str, Ts: NDArray[np.float64], values: dict[str, Any]) -> None:  # fmt: skip
    """Draw poses (n, 4, 4) in the fixed frame with the display's "Shape" options, as the
    scene node ``key`` (replaced; removed when there are none)."""
    if Ts.shape[0] == 0:
        display.remove_node(key)
        return
    shape = str(values["Shape"])
    if shape == "Axes":
        display.add_node(key, "batched_axes", batched_wxyzs=wxyz_from_matrices(Ts[:, :3, :3]),
                         batched_positions=Ts[:, :3, 3],
                         axes_length=float(values["Axes Length"]),
                         axes_radius=float(values["Axes Radius"]))  # fmt: skip
        return
    rgb = color_rgb(values["Color"])
    if shape == "Arrow (Flat)":
        display.add_node(key, "line_segments", points=flat_arrow_segments(Ts, float(values["Arrow Length"])),
                         colors=rgb, thickness=2.0, thickness_units="screen")  # fmt: skip
        return
    head = float(values["Head Length"])
    display.add_node(key, "arrows", points=arrow_segments(Ts, float(values["Shaft Length"]) + head),
                     colors=rgb, shaft_radius=float(values["Shaft Radius"]),
                     head_radius=float(values["Head Radius"]), head_length=head)  # fmt: skip


def draw_covariance(display: Display, key: str, T_fixed_frame: NDArray[np.float64], position_m: NDArray[np.float64], covariance: Any, values: dict[str, Any]) -> None:  # fmt: skip
    """The position covariance's ellipsoid at ``position_m`` (in the message frame, whose pose
    in the fixed frame is ``T_fixed_frame``); the covariance is in the message frame."""
    if not (values["Covariance/Value"] and values["Covariance/Position/Value"]):
        display.remove_node(key)
        return
    R, radii = covariance_ellipsoid(covariance, float(values["Covariance/Position/Scale"]))
    T = np.eye(4)
    T[:3, :3], T[:3, 3] = R, position_m
    T = T_fixed_frame @ T
    display.add_node(key, "icosphere", radius=1.0, color=color_rgb(values["Covariance/Position/Color"]),
                     opacity=float(values["Covariance/Position/Alpha"]),
                     scale=tuple(float(max(r, 1e-6)) for r in radii),
                     wxyz=tuple(wxyz_from_matrices(T[:3, :3])[0]), position=tuple(T[:3, 3]),
                     cast_shadow=False, receive_shadow=False)  # fmt: skip
