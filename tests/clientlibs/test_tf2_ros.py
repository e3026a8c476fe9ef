"""tf2_ros on robomodel's runtime, in-process: the ROS 2 form (a node exposing
``.robomodel_node``, as rclpy's Node does) and the ROS 1 form (the rospy process's node)."""

from __future__ import annotations

import importlib
import sys
import threading
import time
import types
from collections.abc import Iterator
from dataclasses import dataclass
from typing import Any

import numpy as np
import pytest

import robomodel.clientlibs.tf2_ros as tf2_ros
from robomodel.runtime import Context


@dataclass
class FaceNode:
    """What tf2_ros uses of an rclpy Node: its robomodel node."""

    robomodel_node: Any


@dataclass(frozen=True)
class Stamp:
    """rclpy.time.Time / rclpy.duration.Duration: ``nanoseconds``."""

    nanoseconds: int


@dataclass(frozen=True)
class Ros1Time:
    """rospy.Time / rospy.Duration: ``to_nsec`` and ``to_sec``."""

    ns: int

    def to_nsec(self) -> int:
        return self.ns

    def to_sec(self) -> float:
        return self.ns / 1e9


@pytest.fixture
def context() -> Iterator[Context]:
    with Context("inproc") as ctx:
        yield ctx


def _transform(parent: str, child: str, x: float, stamp_ns: int = 0, yaw: float = 0.0) -> Any:
    msg = importlib.import_module("geometry_msgs.msg").TransformStamped()
    msg.header.frame_id = parent
    msg.header.stamp.sec, msg.header.stamp.nanosec = divmod(stamp_ns, 1_000_000_000)
    msg.child_frame_id = child
    msg.transform.translation.x = x
    msg.transform.rotation.z, msg.transform.rotation.w = np.sin(yaw / 2), np.cos(yaw / 2)
    return msg


def test_tf2_ros_is_the_same_module_under_ros_s_names() -> None:
    assert importlib.import_module("tf2_ros") is tf2_ros
    from tf2_ros.buffer import Buffer  # type: ignore[import-not-found]
    from tf2_ros.transform_listener import (  # type: ignore[import-not-found]
        TransformListener,
    )

    assert Buffer is tf2_ros.Buffer and TransformListener is tf2_ros.TransformListener
    assert all(hasattr(tf2_ros, name) for name in tf2_ros.__all__)


def test_a_broadcast_transform_is_looked_up_through_a_listener(context: Context) -> None:
    talker = FaceNode(context.create_node("talker"))
    listener_node = FaceNode(context.create_node("listener"))
    buffer = tf2_ros.Buffer()
    tf2_ros.TransformListener(buffer, listener_node)
    broadcaster = tf2_ros.TransformBroadcaster(talker)
    broadcaster.sendTransform(
        [
            _transform("world", "base", 1.0, 5_000_000_000),
            _transform("base", "arm", 0.5, 5_000_000_000),
        ]
    )
    context.spin_once(0.1)
    found = buffer.lookup_transform("world", "arm", Stamp(0))
    assert type(found) is importlib.import_module("geometry_msgs.msg").TransformStamped
    assert (found.header.frame_id, found.child_frame_id) == ("world", "arm")
    assert found.transform.translation.x == pytest.approx(1.5)
    assert (found.header.stamp.sec, found.header.stamp.nanosec) == (5, 0)
    assert buffer.can_transform("arm", "world", Ros1Time(5_000_000_000))
    assert not buffer.can_transform("world", "camera", Stamp(0))
    ok, why = buffer.can_transform("world", "camera", Stamp(0), return_debug_tuple=True)
    assert not ok and "camera" in why
    with pytest.raises(tf2_ros.LookupException) as caught:
        buffer.lookup_transform("world", "camera", Stamp(0))
    assert isinstance(caught.value, tf2_ros.TransformException)
    with pytest.raises(tf2_ros.ExtrapolationException):
        buffer.lookup_transform("world", "arm", Stamp(9_000_000_000))


def test_the_listener_clears_the_buffer_when_the_clock_goes_back(context: Context) -> None:
    """tf2_ros's listener on a node with ``use_sim_time``: a simulation reset (/clock back)
    forgets the transforms stamped before it."""
    from robomodel.runtime.msg import Clock, Time

    clock = context.create_node("sim").create_publisher(Clock, "/clock")
    node = context.create_node("listener", parameters={"use_sim_time": True})
    buffer = tf2_ros.Buffer()
    tf2_ros.TransformListener(buffer, FaceNode(node))
    broadcaster = tf2_ros.TransformBroadcaster(FaceNode(context.create_node("talker")))
    for t_s, parent, child in ((10.0, "world", "base"), (1.0, "world", "arm")):
        clock.publish(Clock(Time.from_seconds(t_s)))
        context.spin_once(0.05)
        broadcaster.sendTransform(_transform(parent, child, 1.0, int(t_s * 1e9)))
        context.spin_once(0.05)
    assert buffer.can_transform("world", "arm", Stamp(0))
    assert not buffer.can_transform("world", "base", Stamp(0))  # stamped before the reset


def test_a_lookup_waits_up_to_its_timeout_for_the_transform(context: Context) -> None:
    buffer = tf2_ros.Buffer()
    tf2_ros.TransformListener(buffer, FaceNode(context.create_node("listener")))
    broadcaster = tf2_ros.TransformBroadcaster(FaceNode(context.create_node("talker")))
    asked = threading.Event()
    done = threading.Event()

    def later() -> None:  # the other thread (rospy's, an executor's) that fills the buffer
        asked.wait(10)
        broadcaster.sendTransform(_transform("map", "odom", 2.0))
        while not done.is_set():
            context.spin_once(0.01)

    worker = threading.Thread(target=later)
    worker.start()
    try:
        start = time.monotonic()
        assert not buffer.can_transform("map", "odom", Stamp(0))
        asked.set()
        found = buffer.lookup_transform("map", "odom", Stamp(0), timeout=Stamp(20_000_000_000))
        assert found.transform.translation.x == pytest.approx(2.0)
        assert time.monotonic() - start < 20  # answered when it came, not at the timeout
    finally:
        done.set()
        worker.join()
    start = time.monotonic()
    with pytest.raises(tf2_ros.LookupException):
        buffer.lookup_transform("map", "nowhere", Stamp(0), timeout=Ros1Time(200_000_000))
    assert time.monotonic() - start >= 0.2
    assert not buffer.can_transform("map", "nowhere", Stamp(0), timeout=0.05)


def test_static_transforms_accumulate_and_reach_a_late_listener(context: Context) -> None:
    broadcaster = tf2_ros.StaticTransformBroadcaster(FaceNode(context.create_node("statics")))
    broadcaster.sendTransform(_transform("base", "laser", 0.2))
    broadcaster.sendTransform(_transform("base", "camera", 0.3))
    broadcaster.sendTransform(_transform("base", "laser", 0.25))  # replaces the first
    context.spin_once(0.05)
    buffer = tf2_ros.Buffer()
    tf2_ros.TransformListener(buffer, FaceNode(context.create_node("late")))
    context.spin_once(0.1)
    assert buffer.lookup_transform("laser", "camera", Stamp(0)).transform.translation.x == (
        pytest.approx(0.05)
    )
    # static: valid at any time
    assert buffer.can_transform("base", "laser", Stamp(123_000_000_000))


def test_lookup_transform_full_goes_through_the_fixed_frame() -> None:
    buffer = tf2_ros.Buffer()
    buffer.set_transform_static(_transform("map", "odom", 0.0), "test")
    buffer.set_transform(_transform("odom", "base", 1.0, 1_000_000_000), "test")
    buffer.set_transform(_transform("odom", "base", 3.0, 2_000_000_000, yaw=np.pi / 2), "test")
    found = buffer.lookup_transform_full(
        "base", Stamp(2_000_000_000), "base", Stamp(1_000_000_000), "map"
    )
    # base at t=1 seen from base at t=2: (1,0) in odom is (0,2) in the rotated base at (3,0)
    assert found.transform.translation.x == pytest.approx(0.0, abs=1e-9)
    assert found.transform.translation.y == pytest.approx(2.0)
    assert found.transform.rotation.z == pytest.approx(-np.sin(np.pi / 4))
    assert buffer.can_transform_full("base", Stamp(2_000_000_000), "base", Stamp(0), "map")


def test_ros1_form_uses_the_rospy_process_s_node(
    context: Context, monkeypatch: pytest.MonkeyPatch
) -> None:
    node = context.create_node("rospy_node")
    rospy = types.ModuleType("robomodel.clientlibs.rospy")
    rospy.robomodel_node = lambda: node  # type: ignore[attr-defined]
    monkeypatch.setitem(sys.modules, "robomodel.clientlibs.rospy", rospy)
    buffer = tf2_ros.Buffer(cache_time=Ros1Time(10_000_000_000), debug=False)
    listener = tf2_ros.TransformListener(buffer)
    tf2_ros.TransformBroadcaster().sendTransform(_transform("odom", "base", 4.0, 1))
    context.spin_once(0.1)
    assert buffer.lookup_transform("odom", "base", Ros1Time(0)).transform.translation.x == 4.0
    listener.unregister()
    tf2_ros.TransformBroadcaster().sendTransform(_transform("odom", "base", 5.0, 2))
    context.spin_once(0.1)
    assert buffer.lookup_transform("odom", "base", Ros1Time(0)).transform.translation.x == 4.0


def _stamped(type_name: str, frame: str) -> Any:
    msg = getattr(importlib.import_module("geometry_msgs.msg"), type_name)()
    msg.header.frame_id = frame
    return msg


def test_buffer_transform_moves_stamped_geometry_into_the_target_frame() -> None:
    """As tf2_geometry_msgs' conversions: base is 1 m ahead of odom and turned 90 degrees, so
    a point 2 m ahead of base is at (1, 2) in odom, a vector turns, a pose turns and moves."""
    buffer = tf2_ros.Buffer()
    buffer.set_transform(_transform("odom", "base", 1.0, yaw=np.pi / 2), "test")
    point = _stamped("PointStamped", "base")
    point.point.x = 2.0
    moved = buffer.transform(point, "odom")
    assert type(moved) is type(point) and moved.header.frame_id == "odom"
    assert (moved.point.x, moved.point.y, moved.point.z) == pytest.approx((1.0, 2.0, 0.0))
    assert point.point.x == 2.0 and point.header.frame_id == "base"  # the input is unchanged
    vector = _stamped("Vector3Stamped", "base")
    vector.vector.x = 3.0
    turned = buffer.transform(vector, "odom").vector
    assert (turned.x, turned.y, turned.z) == pytest.approx((0.0, 3.0, 0.0))  # no translation
    pose = _stamped("PoseStamped", "base")
    pose.pose.position.y = 1.0
    pose.pose.orientation.w = 1.0
    in_odom = buffer.transform(pose, "odom", timeout=Stamp(0)).pose
    assert (in_odom.position.x, in_odom.position.y) == pytest.approx((0.0, 0.0))
    q = in_odom.orientation
    assert (q.x, q.y, q.z, q.w) == pytest.approx((0, 0, np.sin(np.pi / 4), np.cos(np.pi / 4)))
    child = buffer.transform(_transform("base", "arm", 0.5), "odom").transform.translation
    assert (child.x, child.y) == pytest.approx((1.0, 0.5))
    full = buffer.transform_full(point, "odom", Stamp(0), "odom").point
    assert (full.x, full.y) == pytest.approx((1.0, 2.0))


def test_buffer_transform_uses_what_user_code_registers() -> None:
    calls: list[str] = []

    class Marker:
        def __init__(self) -> None:
            self.header = _stamped("PointStamped", "base").header

    def do_transform_marker(marker: Marker, transform: Any) -> str:
        calls.append(transform.header.frame_id)
        return "moved"

    buffer = tf2_ros.Buffer()
    buffer.set_transform(_transform("odom", "base", 1.0), "test")
    with pytest.raises(tf2_ros.TypeException, match="Marker is not loaded or supported"):
        buffer.transform(Marker(), "odom")
    tf2_ros.TransformRegistration().add(Marker, do_transform_marker)
    assert buffer.transform(Marker(), "odom") == "moved" and calls == ["odom"]
    with pytest.raises(tf2_ros.LookupException):
        buffer.transform(_stamped("PointStamped", "nowhere"), "odom")


def test_the_async_waits_complete_when_the_transform_arrives() -> None:
    buffer = tf2_ros.Buffer()
    future = buffer.wait_for_transform_async("odom", "base", Stamp(0))
    full = buffer.wait_for_transform_full_async("odom", Stamp(0), "base", Stamp(0), "odom")
    assert not future.done() and not full.done()
    buffer.set_transform(_transform("odom", "elsewhere", 1.0), "test")
    assert not future.done()  # another transform: still waiting
    buffer.set_transform(_transform("odom", "base", 2.0), "test")
    assert future.done() and future.result().transform.translation.x == 2.0
    assert full.done() and full.result().child_frame_id == "base"
    now = buffer.wait_for_transform_async("odom", "base", Stamp(0))
    assert now.done()  # possible already: done at once
    coroutine = buffer.lookup_transform_async("odom", "base", Stamp(0))
    with pytest.raises(StopIteration) as stop:
        coroutine.send(None)
    assert stop.value.value.transform.translation.x == 2.0


def test_what_robomodel_does_not_offer_says_so() -> None:
    buffer = tf2_ros.Buffer()
    buffer.set_transform(_transform("odom", "base", 1.0), "test")
    with pytest.raises(NotImplementedError, match=r"tf2_ros\.Buffer\.transform\(new_type"):
        buffer.transform(_stamped("PointStamped", "base"), "odom", new_type=int)
    with pytest.raises(NotImplementedError, match="spin_thread"):
        tf2_ros.TransformListener(tf2_ros.Buffer(), FaceNode(None), spin_thread=True)
    with pytest.raises(TypeError, match="rclpy Node"):
        tf2_ros.TransformBroadcaster(object())


def test_a_real_tf2_ros_on_the_path_wins_with_its_submodules(
    tmp_path: Any, monkeypatch: pytest.MonkeyPatch
) -> None:
    real = tmp_path / "tf2_ros"
    real.mkdir()
    (real / "__init__.py").write_text("REAL = True\n")
    (real / "buffer.py").write_text("class Buffer:\n    real = True\n")
    saved = {k: v for k, v in sys.modules.items() if k == "tf2_ros" or k.startswith("tf2_ros.")}
    for name in saved:
        monkeypatch.delitem(sys.modules, name)
    monkeypatch.syspath_prepend(str(tmp_path))
    try:
        imported = importlib.import_module("tf2_ros")
        assert getattr(imported, "REAL", False)
        assert importlib.import_module("tf2_ros.buffer").Buffer.real
    finally:
        for name in [k for k in sys.modules if k == "tf2_ros" or k.startswith("tf2_ros.")]:
            del sys.modules[name]
