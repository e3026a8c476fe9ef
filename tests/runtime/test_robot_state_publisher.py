"""robot_state_publisher: the upstream launch tests' scenarios, in-process, plus its rules."""

from __future__ import annotations

import logging
import math

import numpy as np
import pytest

from robomodel.description import read_urdf
from robomodel.errors import RobomodelError
from robomodel.kinematics import Kinematics
from robomodel.runtime import Context, ManualClock
from robomodel.runtime.msg import Header, JointState, String, TFMessage, Time
from robomodel.runtime.nodes.robot_state_publisher import RobotStatePublisher
from robomodel.runtime.tf_listener import TransformListener
from tests.conftest import EXAMPLES

FIXED = """<robot name="test"><link name="link1"/><link name="link2"/>
<joint name="joint1" type="fixed"><parent link="link1"/><child link="link2"/>
<origin xyz="5 0 0" rpy="0 0 1.57"/><axis xyz="0 0 1"/></joint></robot>"""
MOVING = FIXED.replace('type="fixed"', 'type="continuous"')


def _setup(
    description: str, **params: object
) -> tuple[Context, RobotStatePublisher, TransformListener]:
    ctx = Context(clock=ManualClock(10.0))
    rsp = RobotStatePublisher(ctx, description, parameters=params)
    listener = TransformListener(ctx.create_node("test"))
    ctx.spin_once()
    return ctx, rsp, listener


def test_two_links_fixed_joint() -> None:
    _, _, listener = _setup(FIXED)
    t = listener.buffer.lookup_transform("link1", "link2")
    assert t.translation_m == pytest.approx((5.0, 0.0, 0.0))
    assert not listener.buffer.can_transform("base_link", "wim_link")


def test_two_links_fixed_joint_prefix() -> None:
    _, _, listener = _setup(FIXED, frame_prefix="my_prefix/")
    assert listener.buffer.lookup_transform(
        "my_prefix/link1", "my_prefix/link2"
    ).translation_m == pytest.approx((5, 0, 0))


def test_two_links_moving_joint() -> None:
    ctx, _, listener = _setup(MOVING)
    js = ctx.create_node("jsp").create_publisher(JointState, "joint_states")
    js.publish(JointState(Header(Time(10, 0)), ["joint1"], [math.pi]))
    ctx.spin_once()
    t = listener.buffer.lookup_transform("link1", "link2")
    assert t.translation_m == pytest.approx((5.0, 0.0, 0.0))
    # rotation about z by 1.57 (origin) then pi (joint): yaw 1.57 + pi, up to the quaternion sign
    x, y, z, w = t.rotation_xyzw
    assert (x, y) == pytest.approx((0, 0), abs=1e-12)
    assert math.remainder(2 * math.atan2(z, w) - (1.57 + math.pi), 2 * math.pi) == pytest.approx(
        0, abs=1e-12
    )


def test_change_fixed_joint_republishes_static() -> None:
    ctx, rsp, listener = _setup(FIXED)
    descriptions: list[str] = []
    ctx.create_node("watch").create_subscription(
        String, "/robot_description", lambda m: descriptions.append(m.data), 1
    )
    result = rsp.node.set_parameters(
        {"robot_description": FIXED.replace('xyz="5 0 0"', 'xyz="10 0 0"')}
    )
    assert result.successful
    ctx.spin_once()
    assert listener.buffer.lookup_transform("link1", "link2").translation_m == pytest.approx(
        (10, 0, 0)
    )
    assert descriptions and 'xyz="10 0 0"' in descriptions[-1]


def test_change_mimic_joint_regression() -> None:
    mimic = FIXED.replace("</joint>", '<mimic joint="joint1"/></joint>')
    _, rsp, _ = _setup(mimic)
    assert rsp.node.set_parameters(
        {"robot_description": "<robot name='test'><link name='base_link'/></robot>"}
    ).successful
    assert rsp.node.set_parameters({"robot_description": ""}).reason == "Empty URDF is not allowed"
    bad = rsp.node.set_parameters({"robot_description": "<robot name='x'>"})
    assert not bad.successful and "malformed XML" in bad.reason


def test_rate_limit_stamps_unknown_and_mimic() -> None:
    urdf = """<robot name="r"><link name="a"/><link name="b"/><link name="c"/>
    <joint name="j" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
    <joint name="m" type="revolute"><parent link="b"/><child link="c"/><axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="1" velocity="1"/>
      <mimic joint="j" multiplier="2" offset="0.1"/></joint></robot>"""
    ctx, _, _ = _setup(urdf, publish_frequency=20.0)
    sent: list[TFMessage] = []
    ctx.create_node("tap").create_subscription(TFMessage, "/tf", sent.append, 100)
    js = ctx.create_node("jsp").create_publisher(JointState, "joint_states")
    for ms in (0, 20, 49, 50, 100):  # 20 Hz -> one message per 50 ms of stamps
        js.publish(JointState(Header(Time(1, ms * 1_000_000)), ["j", "unknown"], [0.5, 9.0]))
        ctx.spin_once()
    assert [len(m.transforms) for m in sent] == [2, 2, 2]  # j and its mimic m; unknown ignored
    assert [m.transforms[0].header.stamp.nanosec // 1_000_000 for m in sent] == [0, 50, 100]
    mimic_tf = sent[0].transforms[1]
    assert mimic_tf.child_frame_id == "c"
    angle = 2 * math.atan2(mimic_tf.transform.rotation.z, mimic_tf.transform.rotation.w)
    assert angle == pytest.approx(2 * 0.5 + 0.1)
    # An explicit value for the mimic joint wins over the computed one (std::map::insert).
    sent.clear()
    js.publish(JointState(Header(Time(2, 0)), ["j", "m"], [0.5, -1.0]))
    ctx.spin_once()
    angle = 2 * math.atan2(
        sent[0].transforms[1].transform.rotation.z, sent[0].transforms[1].transform.rotation.w
    )
    assert angle == pytest.approx(-1.0)


def test_invalid_messages_are_warned_about(caplog: pytest.LogCaptureFixture) -> None:
    ctx, _, _ = _setup(MOVING)
    js = ctx.create_node("jsp").create_publisher(JointState, "joint_states")
    with caplog.at_level(logging.WARNING):
        js.publish(JointState(Header(Time(1, 0)), ["joint1"], []))
        js.publish(JointState(Header(Time(1, 0)), ["joint1", "x"], [1.0]))
        ctx.spin_once()
    text = caplog.text
    assert (
        'ignored a JointState message about joint(s) "joint1" whose position member was empty'
        in text
    )
    assert "ignored an invalid JointState message" in text


def test_empty_description_is_refused() -> None:
    with pytest.raises(RobomodelError, match="robot_description parameter must not be empty"):
        RobotStatePublisher(Context(clock=ManualClock()))


def test_published_tf_equals_forward_kinematics() -> None:
    robot = read_urdf(EXAMPLES / "gripper_description" / "urdf" / "planar_3dof.urdf").robot
    ctx, _, listener = _setup(
        (EXAMPLES / "gripper_description" / "urdf" / "planar_3dof.urdf").read_text()
    )
    kin = Kinematics(robot)
    q = np.array([0.3, -0.7, 1.1])
    js = ctx.create_node("jsp").create_publisher(JointState, "joint_states")
    js.publish(JointState(Header(Time(10, 0)), list(kin.joint_names), list(q)))
    ctx.spin_once()
    T = kin.fk(q, links=["gripper"])[0]
    looked = listener.buffer.lookup_transform("base_link", "gripper").matrix()
    np.testing.assert_allclose(looked, T, atol=1e-12)


MIXED = """<robot name="mixed"><link name="base"/><link name="a"/><link name="b"/><link name="c"/>
<link name="d"/>
<joint name="rev" type="revolute"><parent link="base"/><child link="a"/>
<origin xyz="0.1 0.2 0.3" rpy="0.4 -0.2 0.9"/><axis xyz="0 0 2"/>
<limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
<joint name="slide" type="prismatic"><parent link="a"/><child link="b"/>
<origin xyz="0.5 0 0" rpy="0 0.7 0"/><axis xyz="1 1 0"/>
<limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
<joint name="spin" type="continuous"><parent link="b"/><child link="c"/>
<origin xyz="0 0 0.2" rpy="1.2 0 0.3"/><axis xyz="0.3 -0.5 0.8"/></joint>
<joint name="weld" type="fixed"><parent link="c"/><child link="d"/>
<origin xyz="0.05 0 0" rpy="0 0 0.5"/></joint></robot>"""


def test_published_tf_equals_forward_kinematics_for_every_joint_kind() -> None:
    """Revolute, prismatic and continuous joints with rotated origins and non-unit axes (KDL
    normalises them), and a fixed joint on /tf_static: each link where FK puts it."""
    robot = read_urdf(MIXED).robot
    ctx, _, listener = _setup(MIXED)
    kin = Kinematics(robot)
    q = np.array([0.8, 0.35, -2.1])
    js = ctx.create_node("jsp").create_publisher(JointState, "joint_states")
    js.publish(JointState(Header(Time(10, 0)), list(kin.joint_names), list(q)))
    ctx.spin_once()
    for link, T in zip(["a", "b", "c", "d"], kin.fk(q, links=["a", "b", "c", "d"]), strict=True):
        looked = listener.buffer.lookup_transform("base", link).matrix()
        np.testing.assert_allclose(looked, T, atol=1e-12, err_msg=link)
