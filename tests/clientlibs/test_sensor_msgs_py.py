"""ROS 2's ``sensor_msgs_py.point_cloud2`` (numpy), checked against a struct-packing reading
and writing of the same layout here (as ROS 1's ``sensor_msgs.point_cloud2`` packs points; the
rospy module itself is not imported: a process that imports rospy gets genpy's classes). The
message classes are imported in the tests, as the first import decides their flavour."""

from __future__ import annotations

import math
import struct
import sys
from typing import Any

import numpy as np
import pytest
from sensor_msgs_py import point_cloud2

_STRUCT = {1: "b", 2: "B", 3: "h", 4: "H", 5: "i", 6: "I", 7: "f", 8: "d"}


def _point_format(fields: list[Any]) -> str:
    """One point's struct format: fields by offset, padding between them."""
    fmt, at = "<", 0
    for field in sorted(fields, key=lambda f: f.offset):
        fmt += "x" * (field.offset - at) + _STRUCT[field.datatype] * field.count
        at = field.offset + struct.calcsize("<" + _STRUCT[field.datatype]) * field.count
    return fmt


def struct_read(cloud: Any) -> list[tuple[Any, ...]]:
    pack = struct.Struct(_point_format(list(cloud.fields)))
    data = bytes(cloud.data)
    return [pack.unpack_from(data, i * cloud.point_step) for i in range(cloud.width)]


def struct_cloud(fields: list[Any], rows: list[tuple[Any, ...]]) -> Any:
    from sensor_msgs.msg import PointCloud2

    pack = struct.Struct(_point_format(fields))
    data = b"".join(pack.pack(*row) for row in rows)
    return PointCloud2(
        header=header(), height=1, width=len(rows), fields=fields, is_bigendian=False,
        point_step=pack.size, row_step=len(data), data=data, is_dense=False,
    )  # fmt: skip


def fields() -> list[Any]:
    from sensor_msgs.msg import PointField

    return [
        PointField(name="x", offset=0, datatype=PointField.FLOAT32, count=1),
        PointField(name="y", offset=4, datatype=PointField.FLOAT32, count=1),
        PointField(name="z", offset=8, datatype=PointField.FLOAT32, count=1),
        PointField(name="ring", offset=12, datatype=PointField.UINT16, count=1),
        PointField(name="rgb", offset=16, datatype=PointField.UINT8, count=3),  # then padding
        PointField(name="n", offset=20, datatype=PointField.FLOAT32, count=2),
    ]


def header() -> Any:
    from std_msgs.msg import Header

    return Header(frame_id="lidar")


ROWS = [
    (1.5, -2.0, 0.25, 7, 10, 20, 30, 0.5, -0.5),
    (math.nan, 4.0, 5.0, 8, 1, 2, 3, 1.0, 2.0),
    (6.0, 7.0, 8.0, 9, 0, 0, 255, -1.0, 0.0),
]


def test_a_cloud_made_here_reads_the_same_through_struct() -> None:
    cloud = point_cloud2.create_cloud(header(), fields(), ROWS)
    assert (cloud.height, cloud.width, cloud.point_step) == (1, 3, 28)
    assert cloud.row_step == 84 and len(cloud.data) == 84
    assert cloud.is_bigendian == (sys.byteorder == "big") and cloud.header.frame_id == "lidar"
    theirs = struct_read(cloud)
    assert len(theirs) == 3
    for ours, row in zip(point_cloud2.read_points_list(cloud), theirs, strict=True):
        assert len(ours) == len(row) == 9
        for a, b in zip(ours, row, strict=True):
            assert (math.isnan(a) and math.isnan(b)) or a == pytest.approx(b)
    names = point_cloud2.read_points(cloud).dtype.names
    assert names == ("x", "y", "z", "ring", "rgb_0", "rgb_1", "rgb_2", "n_0", "n_1")


def test_a_cloud_packed_by_struct_reads_here() -> None:
    cloud = struct_cloud(fields()[:3], [(1.0, 2.0, 3.0), (4, 5, 6)])
    xyz = point_cloud2.read_points_numpy(cloud)
    assert xyz.shape == (2, 3) and xyz.dtype == np.float32
    np.testing.assert_array_equal(xyz, [[1, 2, 3], [4, 5, 6]])
    np.testing.assert_array_equal(
        point_cloud2.read_points_numpy(cloud, field_names=["z", "x"]), [[3, 1], [6, 4]]
    )


def test_nans_uvs_and_organized_clouds() -> None:
    cloud = point_cloud2.create_cloud(header(), fields(), ROWS)
    kept = point_cloud2.read_points(cloud, field_names=["x", "ring"], skip_nans=True)
    assert kept["ring"].tolist() == [7, 9]  # the NaN point dropped
    assert point_cloud2.read_points(cloud, uvs=[2, 0])["ring"].tolist() == [9, 7]
    with pytest.raises(ValueError, match="one datatype"):
        point_cloud2.read_points_numpy(cloud)
    grid = point_cloud2.create_cloud_xyz32(header(), np.arange(18, dtype=np.float32).reshape(6, 3))
    grid.height, grid.width = 2, 3  # the same bytes as two rows of three
    organized = point_cloud2.read_points(grid, reshape_organized_cloud=True)
    assert organized.shape == (2, 3)
    assert organized[1, 0]["x"] == 9.0  # row 1, column 0: the fourth point
    assert point_cloud2.read_points(grid, uvs=[(0, 1)])["x"].tolist() == [9.0]


def test_a_big_endian_cloud_reads_in_the_host_s_order() -> None:
    cloud = point_cloud2.create_cloud_xyz32(header(), [(1.0, -2.0, 3.5)])
    swapped = np.frombuffer(bytes(cloud.data), dtype=np.float32).byteswap().tobytes()
    cloud.data = swapped
    cloud.is_bigendian = sys.byteorder == "little"
    np.testing.assert_array_equal(point_cloud2.read_points_numpy(cloud), [[1.0, -2.0, 3.5]])


def test_an_unknown_datatype_is_named() -> None:
    from sensor_msgs.msg import PointField

    bad = [PointField(name="w", offset=0, datatype=9, count=1)]
    with pytest.raises(ValueError, match=r"'w' has datatype 9; valid are 1 .INT8. to 8"):
        point_cloud2.dtype_from_fields(bad)
