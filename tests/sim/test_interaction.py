"""Interaction (force, teleport, reset, services), divergence detection, NaN commands, two robots."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from robomodel.loading import load
from robomodel.runtime import Context, ManualClock
from robomodel.runtime.msg.types.geometry_msgs import Twist, Vector3
from robomodel.runtime.msg.types.nav_msgs import Odometry
from robomodel.sim import DivergenceError, Placement, Simulation
from robomodel.sim.bus import SimBridge

from .conftest import RRBOT, RRBOT_YAML, SIMPLEBOT, SIMPLEBOT_YAML

ON_GROUND = (0.0, 0.0, 0.076)


def _simplebot(**placement) -> Simulation:  # type: ignore[no-untyped-def]
    sim = Simulation()
    sim.add_robot(load(str(SIMPLEBOT)), placement=Placement(xyz_m=ON_GROUND, **placement))
    return sim


def test_force_on_a_link_pushes_the_robot() -> None:
    sim = _simplebot()
    sim.step(300)
    sim.apply_wrench("base_link", force_n=(0.0, 5.0, 0.0))
    sim.step(500)
    assert sim.data.body("base_link").xpos[1] > 0.05  # pushed sideways (wheels slide)
    sim.apply_wrench("base_link")
    with pytest.raises(Exception, match="unknown link 'base_lnk'"):
        sim.apply_wrench("base_lnk", force_n=(1, 0, 0))


def test_teleport_and_reset() -> None:
    sim = _simplebot()
    sim.step(200)
    sim.teleport((3.0, -1.0, 0.2), (0.0, 0.0, math.pi / 2))
    assert sim.data.body("base_link").xpos == pytest.approx([3.0, -1.0, 0.2])
    sim.step(500)
    assert sim.data.body("base_link").xpos[2] == pytest.approx(0.075, abs=0.005)
    sim.reset()
    assert sim.time_s == 0.0
    assert sim.data.body("base_link").xpos == pytest.approx(ON_GROUND)


def test_services_queue_requests_to_the_loop() -> None:
    context = Context(clock=ManualClock())
    sim = _simplebot()
    SimBridge(sim, context)
    sim.step(100)
    from robomodel.runtime.msg.types import gazebo_msgs as gz
    from robomodel.runtime.msg.types import std_srvs
    from robomodel.runtime.msg.types.builtin_interfaces import Duration
    from robomodel.runtime.msg.types.geometry_msgs import Point, Pose, Quaternion, Vector3, Wrench

    state = gz.ModelState("simplebot", Pose(Point(1, 1, 0.1), Quaternion(0, 0, 0, 1)))
    reply = context.call_service(
        "/gazebo/set_model_state", gz.SetModelState, gz.SetModelState_Request(state)
    )
    assert reply.success, reply.status_message
    unknown = gz.SetModelState_Request(gz.ModelState("nobody"))
    refused = context.call_service("/gazebo/set_model_state", gz.SetModelState, unknown)
    assert not refused.success and "models are: simplebot" in refused.status_message
    sim.step(20)
    assert sim.data.body("base_link").xpos[0] == pytest.approx(1.0, abs=1e-3)
    lift = gz.ApplyBodyWrench_Request(
        body_name="simplebot::base_link",
        wrench=Wrench(force=Vector3(0, 0, 100)),
        duration=Duration.from_seconds(0.5),
    )
    assert context.call_service("/gazebo/apply_body_wrench", gz.ApplyBodyWrench, lift).success
    sim.step(200)
    assert sim.data.body("base_link").xpos[2] > 0.3  # lifted off
    sim.step(400)  # the 0.5 s of the wrench have passed: it is removed
    assert sim.data.xfrc_applied.max() == 0.0
    context.call_service("/gazebo/reset_world", std_srvs.Empty)
    sim.step(10)
    assert sim.time_s < 0.02


def test_divergence_is_detected_and_names_the_body() -> None:
    sim = Simulation()
    sim.add_robot(load(str(RRBOT)))
    sim.step(10)
    sim.data.qvel[1] = math.nan
    with pytest.raises(DivergenceError) as info:
        sim.step(1)
    assert "link3" in str(info.value) and "joint2" in str(info.value)
    assert info.value.name == "link3"


def test_huge_gains_stop_with_a_divergence_error_not_nan() -> None:
    sim = Simulation()
    sim.add_robot(load(str(RRBOT)))
    sim.step(1)
    sim.data.qfrc_applied[0] = 1e200
    with pytest.raises(DivergenceError, match="diverged"):
        sim.step(200)


def test_nan_commands_never_reach_the_physics() -> None:
    """The resource manager holds the last good command; unclaimed (NaN) joints hold still."""
    sim = Simulation()
    sim.add_robot(load(str(RRBOT)))
    system = sim.control(RRBOT_YAML, spawn=["joint_state_controller"])
    hw = system.resources.components[0]
    slot = hw.command_slot("joint1/effort")
    sim.step(20)
    assert sim.data.qfrc_applied[0] == 0.0  # never commanded: NaN slot, no force
    hw.commands[slot] = 5.0
    sim.step(20)
    hw.commands[slot] = math.nan
    sim.step(50)
    assert np.isfinite(sim.data.qpos).all() and np.isfinite(sim.data.qvel).all()
    assert sim.data.qfrc_applied[0] == 5.0


def test_nan_reaching_the_simulated_hardware_is_warned_once() -> None:
    sim = Simulation()
    sim.add_robot(load(str(RRBOT)))
    system = sim.control(RRBOT_YAML, spawn=["joint_state_controller"])
    hw = system.resources.components[0]
    slot = hw.command_slot("joint1/effort")
    hw.commands[slot] = 5.0
    hw.write(0.0, 0.01)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        hw.commands[slot] = math.nan
        hw.write(0.0, 0.01)
        hw.write(0.0, 0.01)
    assert sim.data.qfrc_applied[0] == 0.0
    messages = [str(w.message) for w in caught]
    assert len(messages) == 1 and "joint 'joint1' got a nan effort command" in messages[0]


def test_two_prefixed_robots_in_one_world() -> None:
    context = Context(clock=ManualClock())
    sim = Simulation()
    r1 = sim.add_robot(load(str(SIMPLEBOT)), placement=Placement("r1_", ON_GROUND))
    r2 = sim.add_robot(
        load(str(SIMPLEBOT)), placement=Placement("r2_", (0.0, 2.0, 0.076), (0.0, 0.0, math.pi))
    )
    sim.control(SIMPLEBOT_YAML, prefix="r1_", context=context, namespace="/r1")
    sim.control(SIMPLEBOT_YAML, prefix="r2_", context=context, namespace="/r2")
    SimBridge(sim, context)
    node = context.create_node("test")
    truths: dict[str, Odometry] = {}
    for ns in ("r1", "r2"):
        node.create_subscription(
            Odometry, f"/{ns}/ground_truth/odom", lambda m, ns=ns: truths.__setitem__(ns, m)
        )
    pub1 = node.create_publisher(Twist, "/r1/simplebot_controller/cmd_vel")
    pub2 = node.create_publisher(Twist, "/r2/simplebot_controller/cmd_vel")
    sim.step(300)
    for _ in range(20):
        pub1.publish(Twist(linear=Vector3(0.2, 0.0, 0.0)))
        pub2.publish(Twist(linear=Vector3(0.0, 0.0, 0.0), angular=Vector3(0.0, 0.0, 0.5)))
        sim.step(100)
    p1 = sim.data.body("r1_base_link").xpos
    p2 = sim.data.body("r2_base_link").xpos
    assert p1[0] == pytest.approx(0.4, rel=0.1) and abs(p1[1]) < 0.01
    axle = (sim.data.body("r2_left_wheel").xpos + sim.data.body("r2_right_wheel").xpos) / 2
    assert np.hypot(axle[0] + 0.35, axle[1] - 2.0) < 0.01  # turned in place about its axle
    assert abs(p2[1] - 2.0) > 0.05
    assert truths["r1"].child_frame_id == "r1_base_link"
    assert truths["r2"].pose.pose.position.y == pytest.approx(p2[1], abs=0.02)
    assert (
        r1.body("base_link") == "r1_base_link"
        and r2.joint("left_wheel_joint") == "r2_left_wheel_joint"
    )


def test_two_robots_collide_with_each_other() -> None:
    sim = Simulation()
    sim.add_robot(load(str(SIMPLEBOT)), placement=Placement("a_", ON_GROUND))
    sim.add_robot(load(str(SIMPLEBOT)), placement=Placement("b_", (0.0, 0.0, 0.4)))
    sim.step(1000)
    assert sim.data.body("b_base_link").xpos[2] > 0.12  # resting on top of a_, not through it


def test_ground_truth_tf_and_static_odom_frame() -> None:
    from robomodel.runtime.msg.types.tf2_msgs import TFMessage

    context = Context(clock=ManualClock())
    sim = Simulation()
    sim.add_robot(load(str(SIMPLEBOT)), placement=Placement("", (1.0, 2.0, 0.076), (0, 0, 0.5)))
    bridge = SimBridge(sim, context)
    frames: dict[str, object] = {}
    node = context.create_node("test")

    def keep(msg: TFMessage) -> None:
        for t in msg.transforms:
            frames[t.child_frame_id] = t

    node.create_subscription(TFMessage, "/tf", keep)
    from robomodel.runtime.qos import latched

    node.create_subscription(TFMessage, "/tf_static", keep, latched())
    sim.step(200)
    truth, odom = frames["ground_truth"], frames["odom"]
    assert truth.header.frame_id == "world"  # type: ignore[attr-defined]
    assert truth.transform.translation.x == pytest.approx(1.0, abs=0.01)  # type: ignore[attr-defined]
    assert odom.transform.translation.y == pytest.approx(2.0)  # type: ignore[attr-defined]
    from robomodel.runtime.msg.types import ros_gz_interfaces as rgz

    step = rgz.ControlWorld_Request(rgz.WorldControl(multi_step=3))
    assert context.call_service("/gazebo/step", rgz.ControlWorld, step).success
    assert bridge.pending_steps == 3
