"""Drawing poses as RViz does (arrows, axes, flat arrows) and covariance ellipsoids, shared by
the Pose, PoseWithCovariance, PoseArray, Odometry and Path displays.

The option tables here are RViz's: pose_display.cpp, pose_with_covariance_display.cpp and
odometry_display.cpp name them "Shape", "Color", "Alpha", "Shaft Length", "Shaft Radius",
"Head Length", "Head Radius", "Axes Length", "Axes Radius" (defaults: red-orange 255; 25; 0,
shaft 1 x 0.05, head 0.3 x 0.1, axes 1 x 0.1); covariance_property.cpp gives "Covariance",
"Position" (colour 204; 51; 204, alpha 0.3, scale 1) and "Orientation" (Frame Local, Color
Style Unique, colour 255; 255; 127, alpha 0.5, offset 1, scale 1), saved nested as RViz 2 does
(``Covariance: {Value: true, Position: {Value: true, Color: ...}}``). Alpha is kept for the config; viser's
arrows are opaque.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

from robomodel.viewer._poses import wxyz_from_matrices
from robomodel.viewer.displays.base import Display, Option, OptionKind, color_rgb
from robomodel.viewer.displays.covariance import covariance_shapes
from robomodel.viewer.displays.geometry import arrow_segments, flat_arrow_segments

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
_STYLES = ("Unique", "RGB")
COVARIANCE_OPTIONS = (
    # RViz 2 saves a property with children as {Value: ..., <child>: ...}
    Option("Covariance/Value", True, OptionKind.BOOL, help="Whether to show the covariances."),
    Option("Covariance/Position/Value", True, OptionKind.BOOL),
    Option("Covariance/Position/Color", "204; 51; 204", OptionKind.COLOR),
    Option("Covariance/Position/Alpha", 0.3, OptionKind.FLOAT, minimum=0.0, maximum=1.0),
    Option("Covariance/Position/Scale", 1.0, OptionKind.FLOAT, minimum=0.0),
    Option("Covariance/Orientation/Value", True, OptionKind.BOOL),
    Option("Covariance/Orientation/Frame", "Local", OptionKind.CHOICE, choices=("Local", "Fixed")),
    Option("Covariance/Orientation/Color Style", "Unique", OptionKind.CHOICE, choices=_STYLES),
    Option("Covariance/Orientation/Color", "255; 255; 127", OptionKind.COLOR),
    Option("Covariance/Orientation/Alpha", 0.5, OptionKind.FLOAT, minimum=0.0, maximum=1.0),
    Option("Covariance/Orientation/Offset", 1.0, OptionKind.FLOAT, minimum=0.0),
    Option("Covariance/Orientation/Scale", 1.0, OptionKind.FLOAT, minimum=0.0),
)
_RGB = ((255, 0, 0), (0, 255, 0), (0, 0, 255))


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


def draw_covariance(display: Display, key: str, T_fixed_frame: NDArray[np.float64], T_frame_pose: NDArray[np.float64], covariance: Any, values: dict[str, Any]) -> None:  # fmt: skip
    """RViz's covariance visual (:mod:`.covariance`) of a pose ``T_frame_pose`` in the message
    frame, whose pose in the fixed frame is ``T_fixed_frame``; the covariance is in the message
    frame. Scene nodes ``key`` (the position ellipsoid) and ``key_orientation0..2`` (siblings: a
    child would move with the ellipsoid)."""
    display.remove_node(key)
    for i in range(3):
        display.remove_node(f"{key}_orientation{i}")
    if not values["Covariance/Value"]:
        return  # nothing drawn: the shapes' eigen-decompositions are not worth making
    shapes = covariance_shapes(
        covariance,
        position_scale=float(values["Covariance/Position/Scale"]),
        orientation_scale=float(values["Covariance/Orientation/Scale"]),
        orientation_offset=float(values["Covariance/Orientation/Offset"]),
    )
    if shapes is None:
        return
    T_frame_at = np.eye(4)  # the message frame's axes at the pose's position
    T_frame_at[:3, 3] = T_frame_pose[:3, 3]
    if values["Covariance/Position/Value"]:
        T = T_fixed_frame @ T_frame_at
        T[:3, :3] = T[:3, :3] @ shapes.R_frame_ellipsoid
        display.add_node(key, "icosphere", radius=1.0, color=color_rgb(values["Covariance/Position/Color"]),
                         opacity=float(values["Covariance/Position/Alpha"]),
                         scale=tuple(float(max(r, 1e-6)) for r in shapes.radii_m),
                         wxyz=tuple(wxyz_from_matrices(T[:3, :3])[0]), position=tuple(T[:3, 3]),
                         cast_shadow=False, receive_shadow=False)  # fmt: skip
    if not values["Covariance/Orientation/Value"]:
        return
    local = values["Covariance/Orientation/Frame"] == "Local"
    T = T_fixed_frame @ (T_frame_pose if local else T_frame_at)
    alpha = float(values["Covariance/Orientation/Alpha"])
    unique = values["Covariance/Orientation/Color Style"] == "Unique"
    for i, (vertices, faces) in enumerate(shapes.orientation):
        # setOrientationColorToRGB: roll red, pitch green, yaw (and the 2D yaw) blue
        rgb = color_rgb(values["Covariance/Orientation/Color"]) if unique else _RGB[2 if shapes.is_2d else i]  # fmt: skip
        display.add_node(f"{key}_orientation{i}", "mesh_simple", vertices=vertices, faces=faces, color=rgb,
                         opacity=alpha, side="double", wxyz=tuple(wxyz_from_matrices(T[:3, :3])[0]),
                         position=tuple(T[:3, 3]), cast_shadow=False, receive_shadow=False)  # fmt: skip
