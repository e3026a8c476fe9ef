"""``tf2_ros.Buffer``: transforms over time, looked up with a timeout (ROS 1 and ROS 2 forms).

Built on robomodel's :class:`robomodel.tf.BufferCore`; a lookup with a timeout waits until the
transform can be answered (a listener's callbacks fill the buffer from another thread: rospy's
or the rclpy executor's), then raises tf2's exception for it, as tf2_ros does.
"""

from __future__ import annotations

import threading
import time
from typing import Any

from robomodel.clientlibs.tf2_ros._convert import (
    duration_s,
    from_message,
    time_ns,
    to_message,
)
from robomodel.tf import DEFAULT_CACHE_TIME_NS, BufferCore, TransformError
from robomodel.tf import TransformStamped as _Transform

__all__ = ["Buffer"]


class Buffer:
    """tf2_ros's ``Buffer(cache_time=None, node=None)`` (ROS 2) / ``Buffer(cache_time=None,
    debug=True)`` (ROS 1): ``lookup_transform``, ``lookup_transform_full``, ``can_transform``
    and ``can_transform_full``, with timeouts."""

    def __init__(self, cache_time: Any = None, node: Any = None, debug: bool = True) -> None:
        cache_ns = DEFAULT_CACHE_TIME_NS
        if cache_time is not None:
            cache_ns = round(duration_s(cache_time) * 1e9)
        self._core = BufferCore(cache_ns)
        self._changed = threading.Condition()
        self.node = node  # ROS 2's optional node (tf2_ros serves tf2_frames on it)

    # -- filling -----------------------------------------------------------------------
    def set_transform(self, transform: Any, authority: str) -> bool:
        """Add a ``geometry_msgs/TransformStamped`` (False when tf2 rejects it)."""
        return self._insert(from_message(transform), authority, False)

    def set_transform_static(self, transform: Any, authority: str) -> bool:
        """Add a static ``geometry_msgs/TransformStamped`` (valid at every time)."""
        return self._insert(from_message(transform), authority, True)

    def _insert(self, transform: _Transform, authority: str, is_static: bool) -> bool:
        with self._changed:
            accepted = self._core.set_transform(transform, authority, is_static)
            self._changed.notify_all()
        return accepted

    def clear(self) -> None:
        with self._changed:
            self._core.clear()

    # -- looking up --------------------------------------------------------------------
    def _wait(self, ready: Any, timeout: Any) -> None:
        """Until ``ready()`` or the timeout [tf2 duration] passes."""
        deadline = time.monotonic() + duration_s(timeout)
        with self._changed:
            while not ready():
                left = deadline - time.monotonic()
                if left <= 0:
                    return
                self._changed.wait(left)

    def lookup_transform(
        self, target_frame: str, source_frame: str, time: Any = None, timeout: Any = None
    ) -> Any:
        """The transform from ``source_frame`` to ``target_frame`` at ``time`` (0 or None:
        the latest common time), waiting up to ``timeout``.

        Raises:
            LookupException, ConnectivityException, ExtrapolationException: as tf2_ros.
        """
        stamp = time_ns(time)
        self._wait(lambda: self._core.can_transform(target_frame, source_frame, stamp), timeout)
        with self._changed:
            found = self._core.lookup_transform(target_frame, source_frame, stamp)
        return to_message(found)

    def lookup_transform_full(
        self,
        target_frame: str,
        target_time: Any,
        source_frame: str,
        source_time: Any,
        fixed_frame: str,
        timeout: Any = None,
    ) -> Any:
        """``source_frame`` at ``source_time`` in ``target_frame`` at ``target_time``, through
        ``fixed_frame`` (which does not move between the two times), as tf2's full lookup."""
        target_ns, source_ns = time_ns(target_time), time_ns(source_time)
        self._wait(
            lambda: (
                self._core.can_transform(target_frame, fixed_frame, target_ns)
                and self._core.can_transform(fixed_frame, source_frame, source_ns)
            ),
            timeout,
        )
        with self._changed:
            T_target_fixed = self._core.lookup_transform(target_frame, fixed_frame, target_ns)
            T_fixed_source = self._core.lookup_transform(fixed_frame, source_frame, source_ns)
        composed = _Transform.from_matrix(
            target_frame,
            source_frame,
            T_target_fixed.matrix() @ T_fixed_source.matrix(),
            T_target_fixed.stamp_ns,
        )
        return to_message(composed)

    def can_transform(
        self,
        target_frame: str,
        source_frame: str,
        time: Any = None,
        timeout: Any = None,
        return_debug_tuple: bool = False,
    ) -> Any:
        """Whether the transform can be looked up, waiting up to ``timeout``
        (``(bool, error text)`` with ``return_debug_tuple``, as tf2_ros)."""
        stamp = time_ns(time)
        self._wait(lambda: self._core.can_transform(target_frame, source_frame, stamp), timeout)
        return self._answer(lambda: self._core.lookup_transform(target_frame, source_frame, stamp),
                            return_debug_tuple)  # fmt: skip

    def can_transform_full(
        self,
        target_frame: str,
        target_time: Any,
        source_frame: str,
        source_time: Any,
        fixed_frame: str,
        timeout: Any = None,
        return_debug_tuple: bool = False,
    ) -> Any:
        """:meth:`can_transform` for :meth:`lookup_transform_full`."""

        def lookup() -> Any:
            return self.lookup_transform_full(
                target_frame, target_time, source_frame, source_time, fixed_frame, timeout
            )

        return self._answer(lookup, return_debug_tuple)

    def _answer(self, lookup: Any, return_debug_tuple: bool) -> Any:
        try:
            with self._changed:
                lookup()
        except TransformError as exc:
            return (False, str(exc)) if return_debug_tuple else False
        return (True, "") if return_debug_tuple else True

    # -- introspection -----------------------------------------------------------------
    def all_frames_as_yaml(self) -> str:
        with self._changed:
            return self._core.all_frames_as_yaml()

    def all_frames_as_string(self) -> str:
        with self._changed:
            return self._core.all_frames_as_string()

    def _frameExists(self, frame_id: str) -> bool:
        with self._changed:
            return frame_id in self._core.frames

    # -- what robomodel does not offer -------------------------------------------------
    def transform(self, *args: Any, **kwargs: Any) -> Any:
        """tf2_ros's ``Buffer.transform`` needs tf2_geometry_msgs' registered conversions."""
        raise NotImplementedError(
            "tf2_ros.Buffer.transform (tf2_geometry_msgs' conversions) is not offered by "
            "robomodel: look the transform up with lookup_transform and apply it"
        )

    def lookup_transform_async(self, *args: Any, **kwargs: Any) -> Any:
        raise NotImplementedError(
            "tf2_ros.Buffer.lookup_transform_async is not offered by robomodel: use "
            "lookup_transform with a timeout"
        )

    def wait_for_transform_async(self, *args: Any, **kwargs: Any) -> Any:
        raise NotImplementedError(
            "tf2_ros.Buffer.wait_for_transform_async is not offered by robomodel: use "
            "can_transform with a timeout"
        )
