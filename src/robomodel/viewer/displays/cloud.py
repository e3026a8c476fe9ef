"""sensor_msgs/PointCloud2 as numpy arrays: positions and colours by RViz's transformers.

The point records are read in one ``np.frombuffer`` with a structured dtype built from the
message's ``fields`` (offsets, datatypes, ``point_step`` padding, ``is_bigendian``), so a
100,000-point cloud decodes in about a millisecond. Colours follow RViz 2's point cloud
transformers (rviz_default_plugins/displays/pointcloud/transformers/*.cpp): ``RGB8``,
``RGBF32``, ``Intensity``, ``AxisColor`` and ``FlatColor``, with their option names and
defaults, and RViz's choice of default (``RGB8`` when the cloud has an ``rgb``/``rgba`` field,
else the highest score: ``Intensity``; point_cloud_common.cpp, ``updateTransformers``).
Points whose x, y or z is not finite are dropped, as PointCloud2Display::filterOutInvalidPoints.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from robomodel.viewer.displays.laser_scan import rainbow  # RViz's getRainbowColor
from robomodel.viewer.errors import ViewerError
from robomodel.viewer.limits import MAX_CLOUD_POINTS

__all__ = [
    "COLOR_TRANSFORMERS",
    "CloudColorOptions",
    "CloudError",
    "DecodedCloud",
    "cloud_records",
    "color_transformers_for",
    "decode_cloud",
    "default_color_transformer",
    "message_bytes",
]

# sensor_msgs/PointField datatypes -> numpy kinds (PointField.msg: INT8 = 1 ... FLOAT64 = 8)
_DATATYPES = {1: "i1", 2: "u1", 3: "i2", 4: "u2", 5: "i4", 6: "u4", 7: "f4", 8: "f8"}
COLOR_TRANSFORMERS = ("RGB8", "RGBF32", "Intensity", "AxisColor", "FlatColor")
_AXES = {"X": 0, "Y": 1, "Z": 2}


class CloudError(ViewerError):
    """A PointCloud2 that cannot be drawn (the display shows this as its status)."""


@dataclass(frozen=True, slots=True)
class CloudColorOptions:
    """The colour options of RViz's PointCloud2 display, by their RViz names and defaults.

    Attributes:
        transformer: "Color Transformer" (one of COLOR_TRANSFORMERS; "" = RViz's default).
        channel_name: Intensity's "Channel Name" ("intensity"; "intensities" is tried too).
        use_rainbow, invert_rainbow: Intensity's "Use rainbow" (True), "Invert Rainbow".
        min_color, max_color: Intensity's "Min Color" (black), "Max Color" (white), RGB 0-255.
        autocompute_intensity_bounds: "Autocompute Intensity Bounds" (True).
        min_intensity, max_intensity: "Min Intensity" (0), "Max Intensity" (4096).
        axis: AxisColor's "Axis" ("Z").
        autocompute_value_bounds: "Autocompute Value Bounds" (True).
        min_value, max_value: "Min Value" (-10), "Max Value" (10).
        use_fixed_frame: "Use Fixed Frame" (True): colour by the fixed-frame coordinate.
        color: FlatColor's "Color" (white).
    """

    transformer: str = ""
    channel_name: str = "intensity"
    use_rainbow: bool = True
    invert_rainbow: bool = False
    min_color: tuple[int, int, int] = (0, 0, 0)
    max_color: tuple[int, int, int] = (255, 255, 255)
    autocompute_intensity_bounds: bool = True
    min_intensity: float = 0.0
    max_intensity: float = 4096.0
    axis: str = "Z"
    autocompute_value_bounds: bool = True
    min_value: float = -10.0
    max_value: float = 10.0
    use_fixed_frame: bool = True
    color: tuple[int, int, int] = (255, 255, 255)


@dataclass(frozen=True, slots=True)
class DecodedCloud:
    """A cloud's valid points and their colours.

    Attributes:
        points_m: Shape (n, 3) float32, in the cloud's ``header.frame_id`` [m].
        colors: Shape (n, 3) uint8 RGB.
        transformer: The colour transformer used.
        bounds: The (min, max) the colours were scaled over (Intensity, AxisColor), else None.
        dropped: Points dropped for a non-finite x, y or z.
        truncated: Points not drawn: those past ``MAX_CLOUD_POINTS``.
    """

    points_m: NDArray[np.float32]
    colors: NDArray[np.uint8]
    transformer: str
    bounds: tuple[float, float] | None
    dropped: int
    truncated: int = 0


def message_bytes(data: Any) -> bytes:
    """A ``uint8[]`` field as bytes: the codecs decode it as bytes (returned as is, no copy);
    a message built in the same process may hold a list of ints, a bytearray or numpy."""
    return data if isinstance(data, bytes) else bytes(data)


def _field_names(msg: Any) -> list[str]:
    return [f.name for f in msg.fields]


def cloud_records(msg: Any) -> np.ndarray:
    """The cloud's points as a structured array (one record per point, fields by name).

    Raises:
        CloudError: No x/y/z fields, a field outside ``point_step``, an unknown datatype, or
            a data size that is not ``width * height * point_step`` (RViz's own message).
    """
    names = _field_names(msg)
    if not {"x", "y", "z"} <= set(names):
        raise CloudError(f"the cloud has no x, y and z fields (its fields: {', '.join(names)})")
    order = ">" if msg.is_bigendian else "<"
    dtype_fields: dict[str, Any] = {"names": [], "formats": [], "offsets": []}
    for field in msg.fields:
        kind = _DATATYPES.get(int(field.datatype))
        if kind is None:
            raise CloudError(
                f"field '{field.name}' has datatype {field.datatype}; valid are 1-8 (PointField)"
            )
        count = max(int(field.count), 1)
        size = int(kind[1:]) * count
        if field.offset + size > msg.point_step:
            raise CloudError(
                f"field '{field.name}' (offset {field.offset}, {size} bytes) does not fit "
                f"point_step {msg.point_step}"
            )
        if not field.name or field.name in dtype_fields["names"]:
            continue  # RViz finds a channel by its first field of that name
        dtype_fields["names"].append(field.name)
        dtype_fields["formats"].append((order + kind, (count,)) if count > 1 else order + kind)
        dtype_fields["offsets"].append(int(field.offset))
    dtype_fields["itemsize"] = int(msg.point_step)
    n = int(msg.width) * int(msg.height)
    data = message_bytes(msg.data)
    if len(data) != n * msg.point_step:
        raise CloudError(
            f"Data size ({len(data)} bytes) does not match width ({msg.width}) times height "
            f"({msg.height}) times point_step ({msg.point_step}).  Dropping message."
        )
    record: Any = dtype_fields  # numpy's stubs do not type the dict form of a dtype
    return np.frombuffer(data, dtype=np.dtype(record), count=n)


def color_transformers_for(msg: Any) -> tuple[str, ...]:
    """The colour transformers that support this cloud (RViz's "Color Transformer" options)."""
    fields = {f.name: int(f.datatype) for f in msg.fields}
    found = []
    rgb = fields.get("rgb", fields.get("rgba"))
    if rgb in (5, 6, 7):  # RGB8PCTransformer::supports: INT32, UINT32 or FLOAT32
        found.append("RGB8")
    if {"r", "g", "b"} <= fields.keys() and fields["r"] == 7:  # RGBF32: FLOAT32
        found.append("RGBF32")
    return (*found, "Intensity", "AxisColor", "FlatColor")


def default_color_transformer(msg: Any) -> str:
    """RViz's choice: RGB8 when supported, else the best score (Intensity, 255)."""
    return "RGB8" if "RGB8" in color_transformers_for(msg) else "Intensity"


def _to_uint8(rgb01: NDArray[np.floating[Any]]) -> NDArray[np.uint8]:
    return np.asarray(np.clip(rgb01, 0.0, 1.0) * 255.0 + 0.5, dtype=np.float32).astype(np.uint8)


def _scalar(records: np.ndarray, name: str) -> NDArray[np.float64]:
    values = records[name]
    return np.asarray(values if values.ndim == 1 else values[:, 0], dtype=np.float64)


def _bounds(values: NDArray[np.float64], auto: bool, lo: float, hi: float) -> tuple[float, float]:
    if auto and values.size:
        return float(values.min()), float(values.max())
    return float(lo), float(hi)


def _intensity_colors(records: np.ndarray, opts: CloudColorOptions) -> tuple[NDArray[np.uint8], tuple[float, float] | None]:  # fmt: skip
    names = records.dtype.names or ()
    channel = opts.channel_name
    if channel not in names and channel == "intensity" and "intensities" in names:
        channel = "intensities"
    if channel not in names:  # RViz leaves the points white
        return np.full((records.shape[0], 3), 255, dtype=np.uint8), None
    values = _scalar(records, channel)
    lo, hi = _bounds(values, opts.autocompute_intensity_bounds, opts.min_intensity, opts.max_intensity)  # fmt: skip
    lo, hi = max(lo, -999999.0), min(hi, 999999.0)
    diff = hi - lo if hi != lo else 1e20  # equal bounds: one predictable colour (RViz)
    if opts.use_rainbow:
        value = 1.0 - (values - lo) / diff
        return rainbow(1.0 - value if opts.invert_rainbow else value), (lo, hi)
    t = np.clip((values - lo) / diff, 0.0, 1.0)[:, None]
    lo_rgb = np.asarray(opts.min_color, dtype=np.float64) / 255.0
    hi_rgb = np.asarray(opts.max_color, dtype=np.float64) / 255.0
    return _to_uint8(hi_rgb * t + lo_rgb * (1.0 - t)), (lo, hi)


def _axis_colors(points_m: NDArray[np.float32], opts: CloudColorOptions, T_fixed_cloud: NDArray[np.float64] | None) -> tuple[NDArray[np.uint8], tuple[float, float]]:  # fmt: skip
    if opts.axis not in _AXES:
        raise CloudError(f"AxisColor axis must be X, Y or Z, got {opts.axis!r}")
    k = _AXES[opts.axis]
    if opts.use_fixed_frame and T_fixed_cloud is not None:
        values = points_m.astype(np.float64) @ T_fixed_cloud[k, :3] + T_fixed_cloud[k, 3]
    else:
        values = points_m[:, k].astype(np.float64)
    lo, hi = _bounds(values, opts.autocompute_value_bounds, opts.min_value, opts.max_value)
    span = hi - lo if hi != lo else 0.001
    return rainbow(1.0 - (values - lo) / span), (lo, hi)


def _rgb8_colors(records: np.ndarray, big_endian: bool) -> NDArray[np.uint8]:
    name = "rgb" if "rgb" in (records.dtype.names or ()) else "rgba"
    raw = np.ascontiguousarray(records[name]).view(">u4" if big_endian else "<u4")
    packed = raw.reshape(-1).astype(np.uint32)
    return np.stack([(packed >> 16) & 0xFF, (packed >> 8) & 0xFF, packed & 0xFF], axis=1).astype(
        np.uint8
    )


def _colors(records: np.ndarray, points_m: NDArray[np.float32], name: str, opts: CloudColorOptions, big_endian: bool, T: NDArray[np.float64] | None) -> tuple[NDArray[np.uint8], tuple[float, float] | None]:  # fmt: skip
    if name == "RGB8":
        return _rgb8_colors(records, big_endian), None
    if name == "RGBF32":
        rgb = np.stack([_scalar(records, c) for c in "rgb"], axis=1)
        return _to_uint8(rgb), None
    if name == "Intensity":
        return _intensity_colors(records, opts)
    if name == "AxisColor":
        return _axis_colors(points_m, opts, T)
    return np.tile(np.asarray(opts.color, dtype=np.uint8), (points_m.shape[0], 1)), None


def decode_cloud(
    msg: Any,
    options: CloudColorOptions | None = None,
    *,
    T_fixed_cloud: NDArray[np.float64] | None = None,
) -> DecodedCloud:
    """The cloud's valid points (in its frame) and their colours.

    Args:
        msg: A sensor_msgs/PointCloud2 message.
        options: Colour options; RViz's defaults when None.
        T_fixed_cloud: The cloud frame's pose in the fixed frame (4x4), for AxisColor's
            "Use Fixed Frame".

    Raises:
        CloudError: The cloud cannot be read (see :func:`cloud_records`), or the colour
            transformer asked for does not support it.
    """
    opts = options or CloudColorOptions()
    records = cloud_records(msg)
    truncated = max(0, len(records) - MAX_CLOUD_POINTS)
    if truncated:
        records = records[:MAX_CLOUD_POINTS]  # a view: the rest is never read
    xyz = np.stack([_scalar(records, c) for c in "xyz"], axis=1).astype(np.float32)
    finite = np.isfinite(xyz)
    valid = finite[:, 0] & finite[:, 1] & finite[:, 2]  # faster than .all(axis=1) on (n, 3)
    dropped = int(valid.size - np.count_nonzero(valid))
    if dropped:
        records, xyz = records[valid], xyz[valid]
    name = opts.transformer or default_color_transformer(msg)
    supported = color_transformers_for(msg)
    if name not in supported:
        raise CloudError(
            f"color transformer '{name}' does not support this cloud; "
            f"valid are: {', '.join(supported)}"
        )
    colors, bounds = _colors(records, xyz, name, opts, bool(msg.is_bigendian), T_fixed_cloud)
    xyz.setflags(write=False)
    colors.setflags(write=False)
    return DecodedCloud(xyz, colors, name, bounds, dropped, truncated)
