"""tf2_ros's ROS 1 form on ROS 1's wire: a static and a dynamic broadcaster and a listener
(rospy's process node each) meet through a ROS 1 master over TCPROS."""

from __future__ import annotations

import sys
import types
from collections.abc import Iterator
from typing import Any

import pytest

import robomodel.clientlibs.tf2_ros as tf2_ros
from robomodel.runtime import Context
from robomodel.runtime.transport.ros1.master import Master
from tests.conftest import free_port
from tests.timing import scaled, wait_until


@pytest.fixture
def master_uri() -> Iterator[str]:
    uri = f"http://127.0.0.1:{free_port()}/"
    master = Master(uri, "127.0.0.1")
    try:
        yield uri
    finally:
        master.close()


def _as_rospy(monkeypatch: pytest.MonkeyPatch, node: Any) -> None:
    """The ROS 1 form asks rospy for the process's node (the client libraries' contract)."""
    rospy = types.ModuleType("robomodel.clientlibs.rospy")
    rospy.robomodel_node = lambda: node  # type: ignore[attr-defined]
    monkeypatch.setitem(sys.modules, "robomodel.clientlibs.rospy", rospy)


def test_ros1_form_over_tcpros(master_uri: str, monkeypatch: pytest.MonkeyPatch) -> None:
    from geometry_msgs.msg import TransformStamped  # type: ignore[import-not-found]

    talker_ctx = Context("ros1", master=master_uri)
    listener_ctx = Context("ros1", master=master_uri)
    try:
        _as_rospy(monkeypatch, talker_ctx.create_node("broadcaster"))
        static = tf2_ros.StaticTransformBroadcaster()
        dynamic = tf2_ros.TransformBroadcaster()
        mount = TransformStamped()
        mount.header.frame_id, mount.child_frame_id = "base_link", "laser"
        mount.transform.translation.z = 0.3
        static.sendTransform(mount)
        _as_rospy(monkeypatch, listener_ctx.create_node("listener"))
        buffer = tf2_ros.Buffer()
        tf2_ros.TransformListener(buffer)
        pose = TransformStamped()
        pose.header.frame_id, pose.child_frame_id = "odom", "base_link"
        pose.header.stamp.sec = 7
        pose.transform.translation.x = 2.0

        def arrived() -> bool:
            dynamic.sendTransform(pose)
            talker_ctx.spin_once(0.02)
            listener_ctx.spin_once(0.05)
            return bool(buffer.can_transform("odom", "laser", None))

        wait_until(arrived, scaled(20), what="/tf and the latched /tf_static over TCPROS")
        found = buffer.lookup_transform("odom", "laser", None)
        assert (found.transform.translation.x, found.transform.translation.z) == (2.0, 0.3)
        assert found.header.stamp.sec == 7
    finally:
        listener_ctx.shutdown()
        talker_ctx.shutdown()
