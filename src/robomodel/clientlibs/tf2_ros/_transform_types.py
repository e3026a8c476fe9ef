"""Buffer.transform's conversions: what tf2_geometry_msgs registers for tf2_ros (a stamped
point, vector, pose or transform moved into another frame), and ``TransformRegistration``, where
user code registers its own as with tf2_ros.

A message is recognised by its ROS type name, so every flavour (rosidl's, genpy's, robomodel's
own) converts, and the result is a copy of the input's class.
"""

from __future__ import annotations

import copy
from collections.abc import Callable
from typing import Any, ClassVar

import numpy as np

from robomodel.clientlibs.tf2_ros._convert import from_message, stamp_ns

__all__ = ["TransformRegistration", "do_transform"]

Convert = Callable[[Any, Any], Any]


def _type_name(msg: Any) -> str:
    """``geometry_msgs/msg/PointStamped`` and ROS 1's ``geometry_msgs/PointStamped`` alike."""
    name = str(getattr(msg, "__typename__", "") or getattr(msg, "_type", ""))
    return name.replace("/msg/", "/")


def _moved(msg: Any, transform: Any) -> Any:
    """A copy of ``msg`` with the transform's target frame and stamp in its header."""
    out = copy.deepcopy(msg)
    out.header.frame_id = transform.header.frame_id
    out.header.stamp = copy.deepcopy(transform.header.stamp)
    return out


def _point(T: np.ndarray, p: Any) -> None:
    p.x, p.y, p.z = (float(v) for v in T[:3, :3] @ (p.x, p.y, p.z) + T[:3, 3])


def _orientation(T: np.ndarray, q: Any) -> None:
    from robomodel.tf.message import TransformStamped

    M = T @ TransformStamped("a", "b", (0.0, 0.0, 0.0), (q.x, q.y, q.z, q.w)).matrix()
    q.x, q.y, q.z, q.w = TransformStamped.from_matrix("a", "b", M).rotation_xyzw


def _point_stamped(msg: Any, transform: Any) -> Any:
    out = _moved(msg, transform)
    _point(from_message(transform).matrix(), out.point)
    return out


def _vector3_stamped(msg: Any, transform: Any) -> Any:
    out = _moved(msg, transform)
    v = out.vector
    R = from_message(transform).matrix()[:3, :3]
    v.x, v.y, v.z = (float(c) for c in R @ (v.x, v.y, v.z))
    return out


def _pose_stamped(msg: Any, transform: Any) -> Any:
    out = _moved(msg, transform)
    T = from_message(transform).matrix()
    _point(T, out.pose.position)
    _orientation(T, out.pose.orientation)
    return out


def _pose_with_covariance_stamped(msg: Any, transform: Any) -> Any:
    """The pose moved and its 6x6 covariance rotated (R C R^T per block), as
    tf2_geometry_msgs does."""
    out = _moved(msg, transform)
    T = from_message(transform).matrix()
    _point(T, out.pose.pose.position)
    _orientation(T, out.pose.pose.orientation)
    R6 = np.zeros((6, 6))
    R6[:3, :3] = R6[3:, 3:] = T[:3, :3]
    C = np.asarray(out.pose.covariance, dtype=float).reshape(6, 6)
    out.pose.covariance = type(out.pose.covariance)(float(c) for c in (R6 @ C @ R6.T).ravel())
    return out


def _transform_stamped(msg: Any, transform: Any) -> Any:
    """``msg`` (a child in its header's frame) expressed in the transform's target frame."""
    from robomodel.tf.message import TransformStamped

    out = _moved(msg, transform)
    T = from_message(transform).matrix() @ from_message(msg).matrix()
    composed = TransformStamped.from_matrix("a", "b", T, stamp_ns(msg.header.stamp))
    t, r = out.transform.translation, out.transform.rotation
    t.x, t.y, t.z = composed.translation_m
    r.x, r.y, r.z, r.w = composed.rotation_xyzw
    return out


_BUILT_IN: dict[str, Convert] = {
    "geometry_msgs/PointStamped": _point_stamped,
    "geometry_msgs/Vector3Stamped": _vector3_stamped,
    "geometry_msgs/PoseStamped": _pose_stamped,
    "geometry_msgs/PoseWithCovarianceStamped": _pose_with_covariance_stamped,
    "geometry_msgs/TransformStamped": _transform_stamped,
}


class TransformRegistration:
    """tf2_ros's registry of ``do_transform(msg, transform_stamped)`` functions by class
    (shared by every instance, as tf2_ros's)."""

    __type_map: ClassVar[dict[Any, Convert]] = {}

    def add(self, key: Any, callback: Convert) -> None:
        TransformRegistration.__type_map[key] = callback

    def get(self, key: Any) -> Convert:
        from robomodel.clientlibs.tf2_ros._exceptions import TypeException

        found = TransformRegistration.__type_map.get(key)
        if found is not None:
            return found
        built_in = _BUILT_IN.get(_type_name(key))
        if built_in is not None:
            return built_in
        known = ", ".join(sorted(_BUILT_IN))
        raise TypeException(
            f"Type {getattr(key, '__name__', key)} is not loaded or supported: tf2_ros "
            f"transforms {known} and what TransformRegistration().add registered"
        )


def do_transform(msg: Any, transform: Any) -> Any:
    """``msg`` moved by ``transform`` (a ``geometry_msgs/TransformStamped``)."""
    return TransformRegistration().get(type(msg))(msg, transform)
