"""``sensor_msgs_py.point_cloud2``: ``sensor_msgs/PointCloud2`` as numpy arrays, as ROS 2's
module offers them.

A cloud's ``data`` is ``width * height`` points of ``point_step`` bytes; each ``PointField``
is ``count`` values of its ``datatype`` at its ``offset`` (a field with ``count > 1`` is read
as ``name_0``, ``name_1``, ...; an unnamed one as ``unnamed_field_<index>``). Points read as
numpy structured arrays with those names; :func:`read_points_numpy` gives a plain
``(n_points, n_fields)`` array when the fields share one datatype.
"""

from __future__ import annotations

import array
import sys
from collections import namedtuple
from collections.abc import Iterable, Sequence
from typing import Any

import numpy as np
from numpy.lib import recfunctions

from robomodel.clientlibs.rclpy._support import interface

__all__ = [
    "DUMMY_FIELD_PREFIX",
    "create_cloud",
    "create_cloud_xyz32",
    "dtype_from_fields",
    "read_points",
    "read_points_list",
    "read_points_numpy",
]

DUMMY_FIELD_PREFIX = "unnamed_field"

# sensor_msgs/PointField's datatype constants (INT8 = 1 ... FLOAT64 = 8) as numpy types
_DATATYPES: dict[int, np.dtype[Any]] = {
    1: np.dtype(np.int8),
    2: np.dtype(np.uint8),
    3: np.dtype(np.int16),
    4: np.dtype(np.uint16),
    5: np.dtype(np.int32),
    6: np.dtype(np.uint32),
    7: np.dtype(np.float32),
    8: np.dtype(np.float64),
}


def dtype_from_fields(fields: Iterable[Any], point_step: int | None = None) -> np.dtype[Any]:
    """The numpy dtype of one point of ``fields`` (``point_step`` bytes long when given)."""
    names: list[str] = []
    formats: list[np.dtype[Any]] = []
    offsets: list[int] = []
    for index, field in enumerate(fields):
        kind = _DATATYPES.get(field.datatype)
        if kind is None:
            raise ValueError(
                f"point field {field.name!r} has datatype {field.datatype}; valid are "
                "1 (INT8) to 8 (FLOAT64)"
            )
        if field.count < 1:
            raise ValueError(f"point field {field.name!r} has count {field.count}; it must be > 0")
        name = field.name or f"{DUMMY_FIELD_PREFIX}_{index}"
        for k in range(field.count):
            sub = f"{name}_{k}" if field.count > 1 else name
            if sub in names:
                raise ValueError(f"point field name {sub!r} appears twice")
            names.append(sub)
            formats.append(kind)
            offsets.append(field.offset + k * kind.itemsize)
    if point_step is None:
        return np.dtype({"names": names, "formats": formats, "offsets": offsets})
    return np.dtype(
        {"names": names, "formats": formats, "offsets": offsets, "itemsize": point_step}
    )


def read_points(
    cloud: Any,
    field_names: Sequence[str] | None = None,
    skip_nans: bool = False,
    uvs: Iterable[Any] | None = None,
    reshape_organized_cloud: bool = False,
) -> np.ndarray[Any, Any]:
    """The cloud's points as a structured array (a view of its data where it can be).

    Args:
        cloud: a ``sensor_msgs/PointCloud2``.
        field_names: the fields to read (all by default).
        skip_nans: drop points with a NaN in a field read (of a cloud that is not dense).
        uvs: only these points: flat indices, or ``(u, v)`` pairs (column, row).
        reshape_organized_cloud: shape ``(height, width)`` instead of ``(n_points,)``.
    """
    dtype = dtype_from_fields(cloud.fields, point_step=cloud.point_step)
    points: np.ndarray[Any, Any] = np.frombuffer(
        bytes(cloud.data), dtype=dtype, count=cloud.width * cloud.height
    )
    if field_names is not None:
        points = recfunctions.repack_fields(points[list(field_names)])
    if bool(cloud.is_bigendian) != (sys.byteorder == "big"):
        points = points.byteswap()  # the values in the host's byte order
    if skip_nans and not cloud.is_dense:
        keep = np.ones(len(points), dtype=bool)
        for name in points.dtype.names or ():
            if points.dtype[name].kind == "f":
                keep &= ~np.isnan(points[name])
        points = points[keep]
    if uvs is not None:
        chosen = [_flat_index(uv, cloud.width) for uv in uvs]
        points = points[np.asarray(chosen, dtype=np.intp)]
    if reshape_organized_cloud and cloud.height > 1:
        points = points.reshape(cloud.height, cloud.width)
    return points


def _flat_index(uv: Any, width: int) -> int:
    if isinstance(uv, (int, np.integer)):
        return int(uv)
    u, v = uv
    return int(v) * width + int(u)


def read_points_numpy(
    cloud: Any,
    field_names: Sequence[str] | None = None,
    skip_nans: bool = False,
    uvs: Iterable[Any] | None = None,
    reshape_organized_cloud: bool = False,
) -> np.ndarray[Any, Any]:
    """:func:`read_points` as a plain array, shape ``(n_points, n_fields)``; ValueError when
    the fields read have different datatypes."""
    points = read_points(cloud, field_names, skip_nans, uvs, reshape_organized_cloud)
    kinds = {points.dtype[name] for name in points.dtype.names or ()}
    if len(kinds) > 1:
        raise ValueError(
            "read_points_numpy needs fields of one datatype; these have "
            + ", ".join(sorted(str(k) for k in kinds))
            + " (pick some with field_names, or use read_points)"
        )
    out: np.ndarray[Any, Any] = recfunctions.structured_to_unstructured(points)
    return out


def read_points_list(
    cloud: Any,
    field_names: Sequence[str] | None = None,
    skip_nans: bool = False,
    uvs: Iterable[Any] | None = None,
) -> list[Any]:
    """The points as a list of ``Point`` named tuples (one attribute per field read)."""
    points = read_points(cloud, field_names, skip_nans, uvs)
    point = namedtuple("Point", points.dtype.names or ())  # type: ignore[misc]
    return [point._make(p) for p in points.tolist()]


def create_cloud(header: Any, fields: Sequence[Any], points: Any) -> Any:
    """A ``sensor_msgs/PointCloud2`` of one row holding ``points``: a structured array with
    the fields' names, or rows of values in the fields' order (an ``(n, n_fields)`` array or
    a list of tuples)."""
    dtype = dtype_from_fields(fields)
    if isinstance(points, np.ndarray) and points.dtype.names is not None:
        packed = np.empty(len(points), dtype=dtype)
        for name in dtype.names or ():
            packed[name] = points[name]
    else:
        rows = np.asarray(points if isinstance(points, np.ndarray) else list(points))
        rows = rows.reshape(len(rows), -1) if rows.size else rows.reshape(0, len(dtype.names or ()))
        packed = recfunctions.unstructured_to_structured(rows, dtype=dtype)
    data = array.array("B")
    data.frombytes(packed.tobytes())
    cloud_class = interface("sensor_msgs.msg", "PointCloud2")
    return cloud_class(
        header=header,
        height=1,
        width=len(packed),
        is_dense=False,
        is_bigendian=sys.byteorder == "big",
        fields=list(fields),
        point_step=dtype.itemsize,
        row_step=dtype.itemsize * len(packed),
        data=data,
    )


def create_cloud_xyz32(header: Any, points: Any) -> Any:
    """A cloud of ``x``, ``y``, ``z`` FLOAT32 fields from ``(n, 3)`` points [m]."""
    field_class = interface("sensor_msgs.msg", "PointField")
    fields = [
        field_class(name=name, offset=4 * i, datatype=7, count=1) for i, name in enumerate("xyz")
    ]
    return create_cloud(header, fields, points)
