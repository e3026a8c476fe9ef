"""``tf2_ros.Buffer``: transforms over time, looked up with a timeout (ROS 1 and ROS 2 forms).

Built on robomodel's :class:`robomodel.tf.BufferCore`; a lookup with a timeout waits until the
transform can be answered (a listener's callbacks fill the buffer from another thread: rospy's
or the rclpy executor's), then raises tf2's exception for it, as tf2_ros does. The async forms
return an rclpy future completed by the transform that made the lookup possible (``await`` it in
a coroutine callback), and ``transform`` moves a stamped message with tf2_geometry_msgs'
conversions.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable
from typing import Any

from robomodel.clientlibs.tf2_ros._convert import (
    duration_s,
    from_message,
    time_ns,
    to_message,
)
from robomodel.clientlibs.tf2_ros._transform_types import TransformRegistration
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
        self._on_new_data: list[Callable[[], None]] = []  # the async waits, tried on each insert
        self.registration = TransformRegistration()
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
            waiting = list(self._on_new_data)
        for try_again in waiting:  # outside the lock: a done future runs callbacks
            try_again()
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

    # -- asynchronous (rclpy futures) ---------------------------------------------------
    def wait_for_transform_async(self, target_frame: str, source_frame: str, time: Any) -> Any:
        """An ``rclpy.task.Future`` done with the transform once it can be looked up (at once
        if it can now)."""
        stamp = time_ns(time)
        return self._when(
            lambda: self._core.can_transform(target_frame, source_frame, stamp),
            lambda: self.lookup_transform(target_frame, source_frame, time),
        )

    def wait_for_transform_full_async(
        self,
        target_frame: str,
        target_time: Any,
        source_frame: str,
        source_time: Any,
        fixed_frame: str,
    ) -> Any:
        """:meth:`wait_for_transform_async` for :meth:`lookup_transform_full`."""
        target_ns, source_ns = time_ns(target_time), time_ns(source_time)
        return self._when(
            lambda: (
                self._core.can_transform(target_frame, fixed_frame, target_ns)
                and self._core.can_transform(fixed_frame, source_frame, source_ns)
            ),
            lambda: self.lookup_transform_full(
                target_frame, target_time, source_frame, source_time, fixed_frame
            ),
        )

    async def lookup_transform_async(self, target_frame: str, source_frame: str, time: Any) -> Any:
        """``await`` it in a coroutine callback: the transform, once it can be looked up."""
        return await self.wait_for_transform_async(target_frame, source_frame, time)

    async def lookup_transform_full_async(
        self,
        target_frame: str,
        target_time: Any,
        source_frame: str,
        source_time: Any,
        fixed_frame: str,
    ) -> Any:
        return await self.wait_for_transform_full_async(
            target_frame, target_time, source_frame, source_time, fixed_frame
        )

    def _when(self, ready: Callable[[], bool], lookup: Callable[[], Any]) -> Any:
        """A future completed by ``lookup()`` the first time ``ready()`` holds (now or after
        an insert); an error of ``lookup`` completes it with that exception."""
        from robomodel.clientlibs.rclpy.task import Future

        future = Future()

        def try_now() -> None:
            if future.done():
                return
            try:
                with self._changed:
                    if not ready():
                        return
                result = lookup()
            except Exception as exc:
                future.set_exception(exc)
            else:
                future.set_result(result)
            with self._changed:
                if try_now in self._on_new_data:
                    self._on_new_data.remove(try_now)

        with self._changed:
            self._on_new_data.append(try_now)
        try_now()
        return future

    # -- moving messages ------------------------------------------------------------------
    def transform(
        self, object_stamped: Any, target_frame: str, timeout: Any = None, new_type: Any = None
    ) -> Any:
        """``object_stamped`` (a stamped point, vector, pose, pose with covariance or
        transform, or a type registered with ``TransformRegistration``) in ``target_frame``,
        looked up at its header's stamp, waiting up to ``timeout``."""
        header = object_stamped.header
        found = self.lookup_transform(target_frame, header.frame_id, header.stamp, timeout)
        return self._converted(self.registration.get(type(object_stamped))(object_stamped, found),
                               new_type)  # fmt: skip

    def transform_full(
        self,
        object_stamped: Any,
        target_frame: str,
        target_time: Any,
        fixed_frame: str,
        timeout: Any = None,
        new_type: Any = None,
    ) -> Any:
        """:meth:`transform` through ``fixed_frame`` to ``target_frame`` at ``target_time``."""
        header = object_stamped.header
        found = self.lookup_transform_full(
            target_frame, target_time, header.frame_id, header.stamp, fixed_frame, timeout
        )
        return self._converted(self.registration.get(type(object_stamped))(object_stamped, found),
                               new_type)  # fmt: skip

    @staticmethod
    def _converted(result: Any, new_type: Any) -> Any:
        if new_type is None or isinstance(result, new_type):
            return result
        raise NotImplementedError(
            "tf2_ros.Buffer.transform(new_type=...) (tf2's convert between types) is not "
            "offered by robomodel: convert the transformed message yourself"
        )
