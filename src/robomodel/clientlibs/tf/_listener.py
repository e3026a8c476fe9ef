"""tf's ``Transformer`` (a buffer of transforms), ``TransformerROS`` (with message helpers)
and ``TransformListener`` (filled from ``/tf`` and ``/tf_static``), on robomodel's TF buffer."""

from __future__ import annotations

import copy
import threading
import time as _time
from typing import Any

import numpy as np
from numpy.typing import NDArray

from robomodel.clientlibs.tf import transformations
from robomodel.clientlibs.tf._broadcaster import stamp_ns
from robomodel.tf import BufferCore
from robomodel.tf import TransformStamped as TransformValue
from robomodel.tf.exceptions import (
    ConnectivityError,
    ExtrapolationError,
    TransformError,
)
from robomodel.tf.exceptions import LookupError as TfLookupError

__all__ = [
    "ConnectivityException",
    "Exception",
    "ExtrapolationException",
    "LookupException",
    "TransformListener",
    "Transformer",
    "TransformerROS",
]

# tf's exceptions are tf2's: robomodel's TF buffer raises the same family
Exception = TransformError
LookupException = TfLookupError
ConnectivityException = ConnectivityError
ExtrapolationException = ExtrapolationError

_DEFAULT_CACHE_S = 10.0


def _frame(frame_id: str) -> str:
    """A frame id as tf hands it to tf2: one leading ``/`` stripped (tf's
    ``strip_leading_slash``; ROS 1 code names frames ``/turtle1``)."""
    return frame_id[1:] if frame_id.startswith("/") else frame_id


def _seconds(duration: Any) -> float:
    return float(duration.to_sec()) if hasattr(duration, "to_sec") else float(duration)


def _rospy_time(ns: int) -> Any:
    from robomodel.clientlibs.rospy.rostime import Time

    return Time(ns // 1_000_000_000, ns % 1_000_000_000)


class _LockedBuffer(BufferCore):
    """A TF buffer that the node's callback thread fills while the user's thread reads it."""

    def __init__(self, cache_time_ns: int) -> None:
        super().__init__(cache_time_ns)
        self.lock = threading.RLock()

    def set_transform(
        self, transform: TransformValue, authority: str, is_static: bool = False
    ) -> bool:
        with self.lock:
            return super().set_transform(transform, authority, is_static)

    def lookup_transform(self, target: str, source: str, time_ns: int = 0) -> TransformValue:
        with self.lock:
            return super().lookup_transform(target, source, time_ns)

    def can_transform(self, target: str, source: str, time_ns: int = 0) -> bool:
        with self.lock:
            return super().can_transform(target, source, time_ns)

    def latest_common_time_ns(self, target: str, source: str) -> int:
        with self.lock:
            return super().latest_common_time_ns(target, source)

    def clear(self) -> None:
        with self.lock:
            super().clear()


class Transformer:
    """A buffer of transforms between frames over time (tf's ``Transformer``)."""

    def __init__(self, interpolate: bool = True, cache_time: Any = None) -> None:
        if not interpolate:
            raise NotImplementedError("tf Transformer(interpolate=False) is not offered")
        cache_s = _DEFAULT_CACHE_S if cache_time is None else _seconds(cache_time)
        self.buffer = _LockedBuffer(int(cache_s * 1e9))
        self._lock = self.buffer.lock

    def setTransform(self, transform: Any, authority: str = "default_authority") -> None:
        """Add a ``geometry_msgs/TransformStamped``."""
        t, r = transform.transform.translation, transform.transform.rotation
        value = TransformValue(
            transform.header.frame_id,
            transform.child_frame_id,
            (t.x, t.y, t.z),
            (r.x, r.y, r.z, r.w),
            stamp_ns(transform.header.stamp),
        )
        self.buffer.set_transform(value, authority)

    def lookupTransform(
        self, target_frame: str, source_frame: str, time: Any
    ) -> tuple[tuple[float, float, float], tuple[float, float, float, float]]:
        """``((x, y, z), (qx, qy, qz, qw))``: the pose of ``source_frame`` in
        ``target_frame`` at ``time`` (``rospy.Time(0)``: the latest). tf.LookupException,
        ConnectivityException or ExtrapolationException when it cannot be had."""
        found = self.buffer.lookup_transform(
            _frame(target_frame), _frame(source_frame), stamp_ns(time)
        )
        return found.translation_m, found.rotation_xyzw

    def canTransform(self, target_frame: str, source_frame: str, time: Any) -> bool:
        return self.buffer.can_transform(_frame(target_frame), _frame(source_frame), stamp_ns(time))

    def waitForTransform(
        self,
        target_frame: str,
        source_frame: str,
        time: Any,
        timeout: Any,
        polling_sleep_duration: Any = None,
    ) -> None:
        """Wait until the transform can be looked up; tf.Exception after ``timeout``."""
        from robomodel.clientlibs.rospy import core

        poll_s = 0.01 if polling_sleep_duration is None else _seconds(polling_sleep_duration)
        end = _time.monotonic() + _seconds(timeout)
        while not self.canTransform(target_frame, source_frame, time):
            if core.is_shutdown():
                raise Exception("rospy shutdown while waiting for a transform")
            if _time.monotonic() >= end:
                raise Exception(
                    f"Lookup of {source_frame} in {target_frame} at {stamp_ns(time)} ns did not"
                    f" succeed within {_seconds(timeout)} s"
                )
            _time.sleep(poll_s)

    def getLatestCommonTime(self, source_frame: str, target_frame: str) -> Any:
        """The latest time at which both frames are known (rospy.Time)."""
        return _rospy_time(
            self.buffer.latest_common_time_ns(_frame(target_frame), _frame(source_frame))
        )

    def frameExists(self, frame_id: str) -> bool:
        with self._lock:
            return frame_id.lstrip("/") in self.buffer.frames

    def getFrameStrings(self) -> list[str]:
        with self._lock:
            return list(self.buffer.frames)

    def allFramesAsString(self) -> str:
        with self._lock:
            return self.buffer.all_frames_as_string()

    def allFramesAsYAML(self) -> str:
        with self._lock:
            return self.buffer.all_frames_as_yaml()

    def clear(self) -> None:
        self.buffer.clear()

    def __getattr__(self, name: str) -> Any:
        if name in _NOT_OFFERED:

            def not_offered(*args: Any, **kwargs: Any) -> Any:
                raise NotImplementedError(f"tf {name}() is not offered by robomodel's tf")

            return not_offered
        raise AttributeError(f"'{type(self).__name__}' object has no attribute '{name}'")


_NOT_OFFERED = frozenset(
    {"lookupTransformFull", "waitForTransformFull", "canTransformFull", "lookupTwist",
     "lookupTwistFull", "chain", "allFramesAsDot", "getTFPrefix"}
)  # fmt: skip


class TransformerROS(Transformer):
    """A :class:`Transformer` with tf's helpers for stamped messages and matrices."""

    def fromTranslationRotation(self, translation: Any, rotation: Any) -> NDArray[np.float64]:
        """The 4x4 matrix of a translation [m] and a quaternion ``[x, y, z, w]``."""
        matrix: NDArray[np.float64] = transformations.translation_matrix(
            translation
        ) @ transformations.quaternion_matrix(rotation)
        return matrix

    def asMatrix(self, target_frame: str, hdr: Any) -> NDArray[np.float64]:
        """The 4x4 matrix that takes points in ``hdr.frame_id`` at ``hdr.stamp`` to
        ``target_frame``."""
        translation, rotation = self.lookupTransform(target_frame, hdr.frame_id, hdr.stamp)
        return self.fromTranslationRotation(translation, rotation)

    def _moved(self, target_frame: str, stamped: Any) -> tuple[Any, NDArray[np.float64]]:
        matrix = self.asMatrix(target_frame, stamped.header)
        result = copy.deepcopy(stamped)
        result.header.frame_id = target_frame
        return result, matrix

    def transformPoint(self, target_frame: str, ps: Any) -> Any:
        """A ``geometry_msgs/PointStamped`` in ``target_frame``."""
        result, m = self._moved(target_frame, ps)
        x, y, z = (m @ np.array([ps.point.x, ps.point.y, ps.point.z, 1.0]))[:3]
        result.point.x, result.point.y, result.point.z = float(x), float(y), float(z)
        return result

    def transformVector3(self, target_frame: str, v3s: Any) -> Any:
        """A ``geometry_msgs/Vector3Stamped`` in ``target_frame`` (rotated only)."""
        result, m = self._moved(target_frame, v3s)
        x, y, z = m[:3, :3] @ np.array([v3s.vector.x, v3s.vector.y, v3s.vector.z])
        result.vector.x, result.vector.y, result.vector.z = float(x), float(y), float(z)
        return result

    def transformQuaternion(self, target_frame: str, ps: Any) -> Any:
        """A ``geometry_msgs/QuaternionStamped`` in ``target_frame``."""
        result, m = self._moved(target_frame, ps)
        q = ps.quaternion
        moved = transformations.quaternion_from_matrix(
            m @ transformations.quaternion_matrix([q.x, q.y, q.z, q.w])
        )
        result.quaternion.x, result.quaternion.y, result.quaternion.z, result.quaternion.w = (
            float(v) for v in moved
        )
        return result

    def transformPose(self, target_frame: str, ps: Any) -> Any:
        """A ``geometry_msgs/PoseStamped`` in ``target_frame``."""
        result, m = self._moved(target_frame, ps)
        p, q = ps.pose.position, ps.pose.orientation
        pose = m @ self.fromTranslationRotation((p.x, p.y, p.z), (q.x, q.y, q.z, q.w))
        x, y, z = transformations.translation_from_matrix(pose)
        qx, qy, qz, qw = transformations.quaternion_from_matrix(pose)
        result.pose.position.x, result.pose.position.y, result.pose.position.z = x, y, z
        o = result.pose.orientation
        o.x, o.y, o.z, o.w = float(qx), float(qy), float(qz), float(qw)
        return result


class TransformListener(TransformerROS):
    """A TransformerROS filled from ``/tf`` and ``/tf_static`` by this process's rospy node
    (made after ``rospy.init_node``)."""

    def __init__(self, interpolate: bool = True, cache_time: Any = None) -> None:
        super().__init__(interpolate, cache_time)
        from robomodel.clientlibs.rospy.core import robomodel_node
        from robomodel.runtime.tf_listener import TransformListener as Listener

        self._listener = Listener(robomodel_node(), self.buffer)
