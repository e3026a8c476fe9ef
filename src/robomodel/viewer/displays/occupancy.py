"""nav_msgs/OccupancyGrid as an RGBA texture with RViz's Map display palettes, and its placement.

The palettes transcribe RViz 2's palette_builder.cpp (rviz_default_plugins/displays/map):
"map" greys free (0) white to occupied (100) black, unknown (-1) grey-green 0x708986, values
101-127 green and -128..-2 red to yellow (illegal values made visible); "costmap" and "raw" as
there, and the "Binary representation" variants with their "Binary threshold".
"""

from __future__ import annotations

import functools
import math
from typing import Any

import numpy as np
from numpy.typing import NDArray

from robomodel.viewer.displays.cloud import message_bytes
from robomodel.viewer.displays.geometry import matrix_from_xyz_xyzw
from robomodel.viewer.errors import ViewerError

__all__ = [
    "COLOR_SCHEMES",
    "GridError",
    "grid_rgba",
    "grid_texture_pose",
    "map_palette",
]

COLOR_SCHEMES = ("map", "costmap", "raw")


class GridError(ViewerError):
    """An OccupancyGrid that cannot be drawn (the display shows this as its status)."""


def _illegal_and_unknown(palette: NDArray[np.uint8]) -> None:
    palette[101:128] = (0, 255, 0, 255)  # illegal positive values: green
    i = np.arange(128, 255)
    palette[128:255, 0] = 255  # illegal negative values: red to yellow
    palette[128:255, 1] = (255 * (i - 128)) // (254 - 128)
    palette[128:255, 2] = 0
    palette[128:255, 3] = 255
    palette[255] = (0x70, 0x89, 0x86, 255)  # -1, unknown


@functools.cache
def map_palette(scheme: str = "map", binary: bool = False, threshold: int = 100) -> NDArray[np.uint8]:  # fmt: skip
    """The (256, 4) RGBA palette indexed by the cell value as uint8 (-1 -> 255).

    Raises:
        GridError: An unknown scheme.
    """
    if scheme not in COLOR_SCHEMES:
        raise GridError(f"unknown color scheme '{scheme}'; valid are: {', '.join(COLOR_SCHEMES)}")
    palette = np.zeros((256, 4), dtype=np.uint8)
    i = np.arange(256)
    if scheme == "raw":
        if binary:
            palette[:] = np.where((i >= threshold)[:, None], 255, 0)
            palette[:, 3] = 255
        else:
            palette[:] = np.stack([i, i, i, np.full(256, 255)], axis=1)
        palette.setflags(write=False)
        return palette  # raw has no illegal or unknown colours (makeRawPalette)
    if scheme == "map":
        if binary:
            palette[:threshold] = (255, 255, 255, 255)
            palette[threshold:101] = (0, 0, 0, 255)
        else:
            v = 255 - (255 * i[:101]) // 100
            palette[:101] = np.stack([v, v, v, np.full(101, 255)], axis=1)
    else:  # costmap
        if binary:
            palette[:threshold] = (0, 0, 255, 255)
            palette[threshold:101] = (255, 0, 0, 255)
        else:
            v = (255 * i[1:99]) // 100
            palette[1:99] = np.stack([v, np.zeros(98), 255 - v, np.full(98, 255)], axis=1)
            palette[99] = (0, 255, 255, 255)  # obstacle: cyan
            palette[100] = (255, 0, 255, 255)  # lethal obstacle: purple
    _illegal_and_unknown(palette)
    palette.setflags(write=False)
    return palette


def grid_rgba(
    msg: Any,
    *,
    color_scheme: str = "map",
    binary: bool = False,
    threshold: int = 100,
    alpha: float = 0.7,
) -> NDArray[np.uint8]:
    """The grid as an image (height, width, 4) RGBA uint8 in the map's own row order: row 0
    is the map's y = 0 edge, which viser's image plane puts at its -y side.

    Args:
        msg: A nav_msgs/OccupancyGrid.
        color_scheme, binary, threshold: RViz's "Color Scheme", "Binary representation",
            "Binary threshold".
        alpha: RViz's "Alpha", multiplied into the palette's alpha.

    Raises:
        GridError: Zero size, data not ``width * height`` cells, or non-finite geometry.
    """
    info = msg.info
    w, h = int(info.width), int(info.height)
    o = info.origin
    geometry = (info.resolution, o.position.x, o.position.y, o.position.z,
                o.orientation.x, o.orientation.y, o.orientation.z, o.orientation.w)  # fmt: skip
    if not all(math.isfinite(float(v)) for v in geometry):
        raise GridError("Message contained invalid floating point values (nans or infs)")
    if w == 0 or h == 0:
        raise GridError(f"Map is zero-sized ({w}x{h})")
    if isinstance(msg.data, list):  # int8[] from the codec: ints in -128..127
        flat = np.asarray(msg.data, dtype=np.int8).view(np.uint8)
    else:
        flat = np.frombuffer(message_bytes(msg.data), dtype=np.uint8)
    if flat.size != w * h:
        raise GridError(
            f"Data size doesn't match width*height: width = {w}, height = {h}, "
            f"data size = {flat.size}"
        )
    cells = flat.reshape(h, w)
    rgba = map_palette(color_scheme, binary, int(threshold))[cells]
    rgba[..., 3] = (rgba[..., 3].astype(np.float32) * min(max(alpha, 0.0), 1.0)).astype(np.uint8)
    return rgba


def grid_texture_pose(msg: Any) -> tuple[NDArray[np.float64], float, float]:
    """Where the texture goes: ``(T_frame_centre, width_m, height_m)``.

    The grid's origin pose is its cell (0, 0)'s outer corner (the map's bottom-left), in
    ``header.frame_id``; the texture's centre is half the map's size along the origin's x and
    y axes.
    """
    info = msg.info
    p, q = info.origin.position, info.origin.orientation
    width_m, height_m = info.width * info.resolution, info.height * info.resolution
    T_frame_origin = matrix_from_xyz_xyzw((p.x, p.y, p.z), (q.x, q.y, q.z, q.w))
    T_origin_centre = np.eye(4)
    T_origin_centre[:2, 3] = width_m / 2.0, height_m / 2.0
    return T_frame_origin @ T_origin_centre, float(width_m), float(height_m)
