"""joint_state_publisher against the upstream tests' scenarios and its parameters."""

from __future__ import annotations

import math

import pytest

from robomodel.description import read_urdf
from robomodel.errors import RobomodelError
from robomodel.runtime import Context, ManualClock
from robomodel.runtime.msg import JointState
from robomodel.runtime.nodes.joint_state_publisher import JointStatePublisher, MimicChainError


def _robot(joints: str, links: int = 4) -> object:
    body = "".join(f'<link name="l{i}"/>' for i in range(1, links + 1))
    return read_urdf(f'<robot name="r">{body}{joints}</robot>').robot


def _joint(
    name: str,
    parent: int,
    child: int,
    jtype: str = "revolute",
    extra: str = "",
    limit: str = '<limit lower="-1" upper="1" effort="1" velocity="1"/>',
) -> str:
    return (
        f'<joint name="{name}" type="{jtype}"><parent link="l{parent}"/><child link="l{child}"/>'
        f"{limit}{extra}</joint>"
    )


MIMIC_CHAIN = (
    _joint("j12", 1, 2)
    + _joint("j23", 2, 3, extra='<mimic joint="j12" offset="0.1"/>')
    + _joint("j34", 3, 4, extra='<mimic joint="j23" multiplier="-1"/>')
)


def _collect(ctx: Context) -> list[JointState]:
    got: list[JointState] = []
    ctx.create_node("listener").create_subscription(JointState, "/joint_states", got.append)
    return got


def test_mimic_chain_as_upstream_test() -> None:
    ctx = Context(clock=ManualClock())
    JointStatePublisher(ctx, _robot(MIMIC_CHAIN))  # type: ignore[arg-type]
    got = _collect(ctx)
    ctx.advance(0.1)
    (msg,) = got
    assert dict(zip(msg.name, msg.position, strict=True)) == {
        "j12": 0.0,
        "j23": 0.1,
        "j34": pytest.approx(-0.1),
    }
    assert msg.velocity == [] and msg.effort == []


def test_mimic_cycle_is_an_error() -> None:
    cycle = _joint("j12", 1, 2, extra='<mimic joint="j23"/>') + _joint(
        "j23", 2, 3, extra='<mimic joint="j12"/>'
    )
    with pytest.raises(MimicChainError, match="Found an infinite recursive mimic chain"):
        JointStatePublisher(Context(clock=ManualClock()), _robot(cycle, links=3))  # type: ignore[arg-type]


def test_zero_joints_publishes_nothing() -> None:
    ctx = Context(clock=ManualClock())
    JointStatePublisher(ctx, _robot(_joint("f", 1, 2, "fixed", limit=""), links=2))  # type: ignore[arg-type]
    got = _collect(ctx)
    ctx.advance(1.0)
    assert got == []


def test_64_joints_at_the_default_rate() -> None:
    joints = "".join(_joint(f"j{i}", 1, i) for i in range(2, 66))
    ctx = Context(clock=ManualClock())
    JointStatePublisher(ctx, _robot(joints, links=65))  # type: ignore[arg-type]
    got = _collect(ctx)
    ctx.advance(1.0)
    assert len(got) == 10  # rate defaults to 10 Hz
    assert len(set(got[0].name)) == 64 and len(got[0].position) == 64


def test_types_zeros_limits_and_parameters() -> None:
    joints = (
        _joint(
            "cont",
            1,
            2,
            "continuous",
            limit='<limit lower="-1" upper="1" effort="1" velocity="1"/>',
        )
        + _joint(
            "pos_range", 2, 3, limit='<limit lower="0.5" upper="1.5" effort="1" velocity="1"/>'
        )
        + _joint(
            "soft",
            3,
            4,
            extra='<safety_controller soft_lower_limit="-0.5" soft_upper_limit="0.25" k_velocity="1"/>',
        )
        + _joint("zeroed", 4, 5)
    )
    links = 5
    ctx = Context(clock=ManualClock())
    jsp = JointStatePublisher(
        ctx,
        _robot(joints, links),  # type: ignore[arg-type]
        parameters={"zeros.zeroed": 0.3, "publish_default_velocities": True, "rate": 20},
    )
    assert (jsp.free_joints["cont"].min, jsp.free_joints["cont"].max) == (-math.pi, math.pi)
    assert jsp.free_joints["pos_range"].zero == 1.0  # min > 0: centre of the range
    assert (jsp.free_joints["soft"].min, jsp.free_joints["soft"].max) == (-0.5, 0.25)
    got = _collect(ctx)
    ctx.advance(0.1)
    assert len(got) == 2
    assert dict(zip(got[0].name, got[0].position, strict=True))["zeroed"] == 0.3
    assert got[0].velocity == [0.0] * 4


def test_source_list_set_positions_center_and_randomize() -> None:
    import random

    ctx = Context(clock=ManualClock())
    jsp = JointStatePublisher(ctx, _robot(MIMIC_CHAIN), parameters={"source_list": ["/sim_joints"]})  # type: ignore[arg-type]
    source = ctx.create_node("sim").create_publisher(JointState, "/sim_joints")
    source.publish(JointState(name=["j12", "unknown"], position=[0.5, 9.0]))
    ctx.spin_once()
    assert jsp.positions()["j12"] == 0.5 and jsp.positions()["j23"] == pytest.approx(0.6)
    jsp.set_positions({"j12": 5.0})
    assert jsp.positions()["j12"] == 1.0  # clamped to the limit
    with pytest.raises(RobomodelError, match="a mimic joint follows its source"):
        jsp.set_positions({"j23": 0.0})
    with pytest.raises(RobomodelError, match="free joints: j12"):
        jsp.set_positions({"nope": 0.0})
    jsp.center()
    assert jsp.positions()["j12"] == 0.0
    jsp.randomize(random.Random(1))
    assert -1.0 <= jsp.positions()["j12"] <= 1.0 and jsp.positions()["j12"] != 0.0


def test_delta_sweeps_and_bounces() -> None:
    ctx = Context(clock=ManualClock())
    jsp = JointStatePublisher(ctx, _robot(_joint("j12", 1, 2), links=2), parameters={"delta": 0.4})  # type: ignore[arg-type]
    seen = []
    for _ in range(8):
        jsp.publish()
        seen.append(round(jsp.positions()["j12"], 6))
    assert seen == [0.4, 0.8, 1.0, 0.6, 0.2, -0.2, -0.6, -1.0]


def test_robot_description_topic_reconfigures() -> None:
    from robomodel.runtime import latched
    from robomodel.runtime.msg import String

    ctx = Context(clock=ManualClock())
    jsp = JointStatePublisher(ctx)
    desc = ctx.create_node("rsp").create_publisher(String, "/robot_description", latched())
    desc.publish(
        String(
            '<robot name="r"><link name="l1"/><link name="l2"/>' + _joint("j12", 1, 2) + "</robot>"
        )
    )
    ctx.spin_once()
    assert list(jsp.free_joints) == ["j12"]


def test_publish_now_restarts_the_rate_timer() -> None:
    ctx = Context(clock=ManualClock())
    jsp = JointStatePublisher(ctx, _robot(_joint("j12", 1, 2), links=2))  # type: ignore[arg-type]
    got = _collect(ctx)
    ctx.advance(0.05)
    jsp.set_positions({"j12": 0.5})
    jsp.publish_now()  # a slider moved at t = 0.05 s
    ctx.advance(0.0)  # deliver
    assert [m.position for m in got] == [[0.5]]
    ctx.advance(0.099)  # the tick due at 0.1 s would repeat the values just sent
    assert len(got) == 1
    ctx.advance(0.002)  # one period after the out-of-turn message
    assert len(got) == 2
    ctx.advance(0.1)
    assert len(got) == 3  # and at the rate again from there
