"""``sensor_msgs.point_cloud2`` (ROS 1's helper module, as ros_tutorials' publish_pointcloud2
imports it) against Debian's own ``sensor_msgs/point_cloud2.py``, loaded from its file as an
independent reference (it builds its clouds with the same message classes)."""

from __future__ import annotations

import importlib
import importlib.util
import math
import struct
from pathlib import Path
from types import ModuleType
from typing import Any

import pytest

from robomodel.clientlibs.rospy import point_cloud2 as ours

REFERENCE = Path("/usr/lib/python3/dist-packages/sensor_msgs/point_cloud2.py")


@pytest.fixture(scope="module")
def ref() -> ModuleType:
    if not REFERENCE.exists():
        pytest.fail(f"Debian's sensor_msgs is missing ({REFERENCE}): tools/system-deps installs it")
    spec = importlib.util.spec_from_file_location("debian_point_cloud2", REFERENCE)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _fields() -> list[Any]:
    """x, y, z as FLOAT32, a gap of 4 bytes, then intensity as UINT16 and a FLOAT64 pair."""
    from sensor_msgs.msg import PointField

    return [
        PointField("x", 0, PointField.FLOAT32, 1),
        PointField("y", 4, PointField.FLOAT32, 1),
        PointField("z", 8, PointField.FLOAT32, 1),
        PointField("intensity", 16, PointField.UINT16, 1),
        PointField("pair", 20, PointField.FLOAT64, 2),
    ]


POINTS = [
    (1.5, -2.0, 0.25, 7, 0.1, 0.2),
    (float("nan"), 3.0, 4.0, 65535, -1.0, 1e300),
    (0.0, 0.0, -8.5, 0, 2.5, -3.5),
]


def test_import_sensor_msgs_point_cloud2_gives_this_module() -> None:
    assert importlib.import_module("sensor_msgs.point_cloud2") is ours


def test_create_cloud_packs_as_debians(ref: ModuleType) -> None:
    from std_msgs.msg import Header

    header = Header(frame_id="map")
    mine, theirs = (
        ours.create_cloud(header, _fields(), POINTS),
        ref.create_cloud(header, _fields(), POINTS),
    )
    assert bytes(mine.data) == bytes(theirs.data)
    assert (mine.point_step, mine.row_step, mine.width, mine.height) == (
        theirs.point_step,
        theirs.row_step,
        3,
        1,
    )
    assert mine.point_step == 36 and mine.header.frame_id == "map"
    xyz = ours.create_cloud_xyz32(header, [p[:3] for p in POINTS])
    assert bytes(xyz.data) == bytes(ref.create_cloud_xyz32(header, [p[:3] for p in POINTS]).data)


@pytest.mark.parametrize("field_names", [None, ["z", "x"], ["pair"]])
@pytest.mark.parametrize("skip_nans", [False, True])
def test_read_points_as_debians(ref: ModuleType, field_names: Any, skip_nans: bool) -> None:
    from std_msgs.msg import Header

    cloud = ref.create_cloud(Header(), _fields(), POINTS)
    mine = list(ours.read_points(cloud, field_names, skip_nans))
    theirs = list(ref.read_points(cloud, field_names, skip_nans))
    assert len(mine) == len(theirs) == (2 if skip_nans and field_names != ["pair"] else 3)
    assert all(_same(a, b) for a, b in zip(mine, theirs, strict=True))
    if field_names != ["z", "x"]:
        return  # a field of count 2 fits no namedtuple field: read_points_list fails on it
    mine_list = ours.read_points_list(cloud, field_names, skip_nans)
    theirs_list = ref.read_points_list(cloud, field_names, skip_nans)
    assert [p._fields for p in mine_list] == [p._fields for p in theirs_list]
    assert all(_same(a, b) for a, b in zip(mine_list, theirs_list, strict=True))


def _same(a: tuple[Any, ...], b: tuple[Any, ...]) -> bool:
    return len(a) == len(b) and all(
        (isinstance(x, float) and math.isnan(x) and math.isnan(y)) or x == y
        for x, y in zip(a, b, strict=True)
    )


def test_an_organized_big_endian_cloud_by_uv(ref: ModuleType) -> None:
    from sensor_msgs.msg import PointCloud2, PointField

    rows = [[(u + 10 * v) * 1.0 for u in range(3)] for v in range(2)]
    data = b"".join(struct.pack(">f", value) for row in rows for value in row)
    cloud = PointCloud2(
        height=2,
        width=3,
        fields=[PointField("v", 0, PointField.FLOAT32, 1)],
        is_bigendian=True,
        point_step=4,
        row_step=12,
        data=data,
    )
    uvs = [(2, 1), (0, 0), (1, 1)]
    assert list(ours.read_points(cloud, uvs=uvs)) == [(12.0,), (0.0,), (11.0,)]
    assert list(ours.read_points(cloud)) == list(ref.read_points(cloud))
    assert ours.read_points_list(cloud)[4].v == 11.0


def test_an_unknown_datatype_is_a_clear_error() -> None:
    from sensor_msgs.msg import PointField

    with pytest.raises(ValueError, match="'w' has datatype 9; valid are 1"):
        ours._get_struct_fmt(False, [PointField("w", 0, 9, 1)])
