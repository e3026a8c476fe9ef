"""ROS 1's ``sensor_msgs.point_cloud2`` (the Python module of the sensor_msgs package, which
rospy programs import beside ``sensor_msgs.msg``): ``create_cloud``, ``create_cloud_xyz32``,
``read_points`` and ``read_points_list`` over ``sensor_msgs/PointCloud2``'s packed ``data``.

A point is packed field by field at the field's ``offset``, each field ``count`` values of its
``datatype`` (``PointField.FLOAT32``, ...), little-endian unless ``is_bigendian``; the bytes
between fields are padding. ``import sensor_msgs.point_cloud2`` gives this module."""

from __future__ import annotations

import math
import struct
from collections import namedtuple
from collections.abc import Iterable, Iterator, Sequence
from typing import Any

__all__ = ["create_cloud", "create_cloud_xyz32", "read_points", "read_points_list"]

# sensor_msgs/PointField's datatype constants: struct format character and size [bytes]
_DATATYPES: dict[int, tuple[str, int]] = {
    1: ("b", 1),  # INT8
    2: ("B", 1),  # UINT8
    3: ("h", 2),  # INT16
    4: ("H", 2),  # UINT16
    5: ("i", 4),  # INT32
    6: ("I", 4),  # UINT32
    7: ("f", 4),  # FLOAT32
    8: ("d", 8),  # FLOAT64
}


def _get_struct_fmt(
    is_bigendian: bool, fields: Sequence[Any], field_names: Sequence[str] | None = None
) -> str:
    """The struct format of one point: the named fields (all by default) in offset order, the
    bytes between them skipped as padding (``x``)."""
    fmt = ">" if is_bigendian else "<"
    at = 0
    for field in sorted(fields, key=lambda f: f.offset):
        if field_names is not None and field.name not in field_names:
            continue
        if field.datatype not in _DATATYPES:
            raise ValueError(
                f"point field {field.name!r} has datatype {field.datatype}; valid are 1 (INT8)"
                " to 8 (FLOAT64)"
            )
        if at < field.offset:
            fmt += "x" * (field.offset - at)
            at = field.offset
        char, size = _DATATYPES[field.datatype]
        fmt += char * field.count
        at += size * field.count
    return fmt


def read_points(
    cloud: Any,
    field_names: Sequence[str] | None = None,
    skip_nans: bool = False,
    uvs: Iterable[tuple[int, int]] = (),
) -> Iterator[tuple[Any, ...]]:
    """The points of ``cloud``, each a tuple of the values of ``field_names`` (all fields by
    default); ``skip_nans`` leaves out points with a NaN value; ``uvs`` reads only the points at
    those ``(column, row)`` positions."""
    unpack = struct.Struct(_get_struct_fmt(cloud.is_bigendian, cloud.fields, field_names))
    data = bytes(cloud.data)
    point_step, row_step = cloud.point_step, cloud.row_step
    positions = list(uvs) or [(u, v) for v in range(cloud.height) for u in range(cloud.width)]
    for u, v in positions:
        point = unpack.unpack_from(data, row_step * v + point_step * u)
        if skip_nans and any(isinstance(x, float) and math.isnan(x) for x in point):
            continue
        yield point


def read_points_list(
    cloud: Any,
    field_names: Sequence[str] | None = None,
    skip_nans: bool = False,
    uvs: Iterable[tuple[int, int]] = (),
) -> list[Any]:
    """:func:`read_points` as a list of namedtuples ``Point`` with the fields' names."""
    names = list(field_names) if field_names is not None else [f.name for f in cloud.fields]
    point_type = namedtuple("Point", names)  # type: ignore[misc]
    return [point_type._make(p) for p in read_points(cloud, names, skip_nans, uvs)]


def create_cloud(header: Any, fields: Sequence[Any], points: Iterable[Sequence[Any]]) -> Any:
    """An unorganized ``sensor_msgs/PointCloud2`` (height 1) of ``points``, each a sequence of
    the fields' values in the order of their offsets."""
    from sensor_msgs.msg import PointCloud2  # type: ignore[import-not-found]

    pack = struct.Struct(_get_struct_fmt(False, fields))
    rows = [pack.pack(*point) for point in points]
    return PointCloud2(
        header=header,
        height=1,
        width=len(rows),
        is_dense=False,
        is_bigendian=False,
        fields=list(fields),
        point_step=pack.size,
        row_step=pack.size * len(rows),
        data=b"".join(rows),
    )


def create_cloud_xyz32(header: Any, points: Iterable[Sequence[float]]) -> Any:
    """:func:`create_cloud` of ``x``, ``y``, ``z`` as FLOAT32 [m]."""
    from sensor_msgs.msg import PointField

    fields = [PointField(name, 4 * i, 7, 1) for i, name in enumerate("xyz")]
    return create_cloud(header, fields, points)
