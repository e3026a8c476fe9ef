"""PointCloud2 -> points and colours (robomodel.viewer.displays.cloud) against known clouds and
a per-point struct reading as the independent reference."""

from __future__ import annotations

import struct

import numpy as np
import pytest

from robomodel.runtime.msg import deserialize, get_message_type, serialize
from robomodel.viewer.displays.cloud import (
    CloudColorOptions,
    CloudError,
    color_transformers_for,
    decode_cloud,
    default_color_transformer,
)
from robomodel.viewer.displays.laser_scan import rainbow

PointCloud2 = get_message_type("sensor_msgs/msg/PointCloud2")
PointField = get_message_type("sensor_msgs/msg/PointField")
FLOAT32, UINT32, UINT16, FLOAT64, INT8 = 7, 6, 4, 8, 1


def make_cloud(points, fields, fmt, *, point_step=None, big_endian=False, height=1):
    """A cloud from rows of values packed with struct format ``fmt`` (padding with 'x')."""
    order = ">" if big_endian else "<"
    size = struct.calcsize(order + fmt)
    step = point_step or size
    data = b"".join(struct.pack(order + fmt, *p).ljust(step, b"\xee") for p in points)
    return PointCloud2(
        height=height,
        width=len(points) // height,
        fields=[PointField(name=n, offset=o, datatype=d, count=1) for n, o, d in fields],
        is_bigendian=big_endian,
        point_step=step,
        row_step=step * len(points) // height,
        data=list(data),
        is_dense=False,
    )


XYZ = [("x", 0, FLOAT32), ("y", 4, FLOAT32), ("z", 8, FLOAT32)]


def get_rainbow_color(value: float) -> tuple[float, float, float]:
    """A line-by-line transcription of RViz's getRainbowColor (point_cloud_helpers.hpp)."""
    value = max(min(value, 1.0), 0.0)
    h = value * 5.0 + 1.0
    i = int(np.floor(h))
    f = h - i
    if not i & 1:
        f = 1 - f
    n = 1 - f
    if i <= 1:
        return (n, 0, 1)
    if i == 2:
        return (0, n, 1)
    if i == 3:
        return (0, 1, n)
    if i == 4:
        return (n, 1, 0)
    return (1, n, 0)


def test_rainbow_matches_rviz_transcription() -> None:
    values = np.linspace(-0.2, 1.2, 141)
    ours = rainbow(values)  # shared with the LaserScan display
    theirs = np.round(np.array([get_rainbow_color(float(v)) for v in values]) * 255)
    np.testing.assert_allclose(ours, theirs, atol=1)
    np.testing.assert_array_equal(rainbow(np.array([0.0, 1.0])), [[255, 0, 255], [255, 0, 0]])


def test_rgb8_cloud_known_points_and_colours_through_cdr() -> None:
    # x y z, 4 bytes padding, rgb packed in a float32 as PCL does, then 4 bytes padding
    rgbs = [0xFF0000, 0x00FF00, 0x0000FF]
    pts = [(1.0, 2.0, 3.0), (-1.0, 0.5, 0.0), (0.0, 0.0, -2.5)]
    rows = [
        (*p, struct.unpack("<f", struct.pack("<I", c))[0]) for p, c in zip(pts, rgbs, strict=True)
    ]
    msg = make_cloud(rows, [*XYZ, ("rgb", 16, FLOAT32)], "fff4xf", point_step=24)
    msg = deserialize(serialize(msg), PointCloud2)  # what a subscription hands over
    assert default_color_transformer(msg) == "RGB8"
    cloud = decode_cloud(msg)
    np.testing.assert_array_equal(cloud.points_m, np.array(pts, dtype=np.float32))
    np.testing.assert_array_equal(cloud.colors, [[255, 0, 0], [0, 255, 0], [0, 0, 255]])
    assert cloud.transformer == "RGB8" and cloud.dropped == 0


def test_big_endian_with_padding_and_double_fields_matches_struct_reference() -> None:
    rng = np.random.default_rng(3)
    rows = [(*rng.normal(size=3), float(rng.integers(0, 1000))) for _ in range(50)]
    fields = [("x", 0, FLOAT64), ("y", 8, FLOAT64), ("z", 16, FLOAT64), ("intensity", 28, UINT16)]
    msg = make_cloud([(*r[:3], int(r[3])) for r in rows], fields, "ddd4xH", point_step=32, big_endian=True)  # fmt: skip
    cloud = decode_cloud(msg, CloudColorOptions(use_rainbow=False))
    data = bytes(msg.data)
    ref_xyz = [struct.unpack_from(">ddd", data, 32 * i) for i in range(50)]
    ref_int = np.array([struct.unpack_from(">H", data, 32 * i + 28)[0] for i in range(50)], float)
    np.testing.assert_allclose(cloud.points_m, np.array(ref_xyz, dtype=np.float32))
    lo, hi = ref_int.min(), ref_int.max()
    grey = np.round((ref_int - lo) / (hi - lo) * 255)
    np.testing.assert_allclose(cloud.colors[:, 0], grey, atol=1)
    assert cloud.bounds == (lo, hi)


def test_nan_points_are_dropped_and_counted() -> None:
    rows = [(0.0, 0.0, 0.0), (float("nan"), 1.0, 1.0), (1.0, float("inf"), 0.0), (2.0, 2.0, 2.0)]
    cloud = decode_cloud(make_cloud(rows, XYZ, "fff"))
    np.testing.assert_array_equal(cloud.points_m, [[0, 0, 0], [2, 2, 2]])
    assert cloud.dropped == 2


def test_intensity_rainbow_min_is_red_max_is_magenta_and_invert() -> None:
    rows = [(0.0, 0.0, 0.0, 10.0), (1.0, 0.0, 0.0, 20.0), (2.0, 0.0, 0.0, 30.0)]
    msg = make_cloud(rows, [*XYZ, ("intensity", 12, FLOAT32)], "ffff")
    assert default_color_transformer(msg) == "Intensity"
    cloud = decode_cloud(msg)
    np.testing.assert_array_equal(cloud.colors[0], [255, 0, 0])  # min intensity: red
    np.testing.assert_array_equal(cloud.colors[2], [255, 0, 255])  # max: magenta
    np.testing.assert_array_equal(cloud.colors[1], _u8(get_rainbow_color(0.5)))
    inverted = decode_cloud(msg, CloudColorOptions(invert_rainbow=True))
    np.testing.assert_array_equal(inverted.colors[0], [255, 0, 255])
    fixed = decode_cloud(msg, CloudColorOptions(autocompute_intensity_bounds=False, min_intensity=0, max_intensity=40))  # fmt: skip
    np.testing.assert_array_equal(fixed.colors[0], _u8(get_rainbow_color(1 - 10 / 40)))


def test_intensity_channel_choice_and_fallbacks() -> None:
    rows = [(0.0, 0.0, 0.0, 1.0), (1.0, 0.0, 0.0, 3.0)]
    msg = make_cloud(rows, [*XYZ, ("intensities", 12, FLOAT32)], "ffff")
    np.testing.assert_array_equal(decode_cloud(msg).colors, [[255, 0, 0], [255, 0, 255]])
    other = decode_cloud(msg, CloudColorOptions(channel_name="missing"))
    np.testing.assert_array_equal(other.colors, 255)  # RViz leaves the points white
    by_x = decode_cloud(msg, CloudColorOptions(channel_name="x", use_rainbow=False, min_color=(0, 0, 255), max_color=(255, 0, 0)))  # fmt: skip
    np.testing.assert_array_equal(by_x.colors, [[0, 0, 255], [255, 0, 0]])


def test_axis_color_uses_fixed_frame_when_asked() -> None:
    rows = [(0.0, 0.0, 0.0), (0.0, 0.0, 1.0)]
    msg = make_cloud(rows, XYZ, "fff")
    local = decode_cloud(msg, CloudColorOptions(transformer="AxisColor"))
    np.testing.assert_array_equal(local.colors, [[255, 0, 0], [255, 0, 255]])
    flip = np.diag([1.0, 1.0, -1.0, 1.0])  # the cloud frame upside down in the fixed frame
    fixed = decode_cloud(msg, CloudColorOptions(transformer="AxisColor"), T_fixed_cloud=flip)
    np.testing.assert_array_equal(fixed.colors, [[255, 0, 255], [255, 0, 0]])
    own = decode_cloud(msg, CloudColorOptions(transformer="AxisColor", use_fixed_frame=False), T_fixed_cloud=flip)  # fmt: skip
    np.testing.assert_array_equal(own.colors, local.colors)


def test_rgbf32_flat_and_transformer_options() -> None:
    rows = [(0.0, 0.0, 0.0, 1.0, 0.5, 0.0)]
    fields = [*XYZ, ("r", 12, FLOAT32), ("g", 16, FLOAT32), ("b", 20, FLOAT32)]
    msg = make_cloud(rows, fields, "ffffff")
    assert color_transformers_for(msg) == ("RGBF32", "Intensity", "AxisColor", "FlatColor")
    np.testing.assert_array_equal(decode_cloud(msg, CloudColorOptions(transformer="RGBF32")).colors, [[255, 128, 0]])  # fmt: skip
    flat = decode_cloud(msg, CloudColorOptions(transformer="FlatColor", color=(1, 2, 3)))
    np.testing.assert_array_equal(flat.colors, [[1, 2, 3]])
    with pytest.raises(CloudError, match="'RGB8' does not support"):
        decode_cloud(msg, CloudColorOptions(transformer="RGB8"))


def test_malformed_clouds_are_errors_with_rviz_message() -> None:
    msg = make_cloud([(0.0, 0.0, 0.0)], XYZ, "fff")
    msg.width = 2
    with pytest.raises(CloudError, match=r"Data size \(12 bytes\) does not match width \(2\)"):
        decode_cloud(msg)
    with pytest.raises(CloudError, match="no x, y and z"):
        decode_cloud(make_cloud([(0.0, 0.0)], XYZ[:2], "ff"))
    bad = make_cloud([(0.0, 0.0, 0.0)], [*XYZ[:2], ("z", 10, FLOAT32)], "fff")
    with pytest.raises(CloudError, match="does not fit point_step 12"):
        decode_cloud(bad)


def test_signed_intensity_is_read_signed() -> None:
    rows = [(0.0, 0.0, 0.0, -5), (1.0, 0.0, 0.0, 5)]
    msg = make_cloud(rows, [*XYZ, ("intensity", 12, INT8)], "fffb", point_step=16)
    assert decode_cloud(msg).bounds == (-5.0, 5.0)


def _u8(rgb: tuple[float, float, float]) -> list[int]:
    return [int(c * 255 + 0.5) for c in rgb]
