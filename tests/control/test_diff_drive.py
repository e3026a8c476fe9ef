"""diff_drive_controller's parameters, topics and refusals, as humble's
``diff_drive_controller_parameter.yaml`` and ``diff_drive_controller.cpp`` define them.

In-process: the controller alone (``init`` with a parameter map) or a control system on the
in-process transport with a manual clock.
"""

from __future__ import annotations

import logging
import math
from typing import Any

import pytest

from robomodel.control import ControlSystem, load_controller_config
from robomodel.control.controllers import ControllerError, DiffDriveController
from robomodel.control.controllers.diff_drive import MAX_TWIST, _time
from robomodel.control.controllers.speed_limiter import SpeedLimiter
from robomodel.loading import load
from robomodel.runtime import Context
from robomodel.runtime.clock import ManualClock
from robomodel.runtime.msg import Odometry as OdometryMsg
from robomodel.runtime.msg import TFMessage, Time, Twist, TwistStamped, Vector3
from tests.control.helpers import WHEEL, WHEELS, diff_drive_system

WHEEL_NAMES = {"left_wheel_names": ["l"], "right_wheel_names": ["r"]}
SIZES = {"wheel_separation": 0.5, "wheel_radius": 0.1}


def _controller(**params: Any) -> DiffDriveController:
    c = DiffDriveController()
    c.init("dd", {**WHEEL_NAMES, **SIZES, **params})
    return c


def _limiter_fields(limiter: SpeedLimiter) -> tuple[Any, ...]:
    return (
        limiter.has_velocity_limits, limiter.has_acceleration_limits, limiter.has_jerk_limits,
        limiter.min_velocity, limiter.max_velocity, limiter.min_acceleration,
        limiter.max_acceleration, limiter.min_jerk, limiter.max_jerk,
    )  # fmt: skip


def test_parameter_defaults_are_humble_s() -> None:
    c = _controller()
    assert (c.wheel_separation, c.wheel_radius) == (0.5, 0.1)
    assert (
        c.wheel_separation_multiplier,
        c.left_wheel_radius_multiplier,
        c.right_wheel_radius_multiplier,
    ) == (1.0, 1.0, 1.0)
    assert (c.tf_frame_prefix_enable, c.tf_frame_prefix) == (True, "")
    assert (c.odom_frame_id, c.base_frame_id) == ("odom", "base_link")
    assert c.pose_covariance_diagonal == [0.0] * 6 == c.twist_covariance_diagonal
    assert (c.open_loop, c.position_feedback, c.enable_odom_tf) == (False, True, True)
    assert (c.cmd_vel_timeout_s, c.publish_rate_hz) == (0.5, 50.0)
    assert (c.publish_limited_velocity, c.use_stamped_vel) == (False, True)
    assert c.velocity_rolling_window_size == 10
    assert c.unstamped_topic == "~/cmd_vel_unstamped"
    for limiter in (c.limiter_linear, c.limiter_angular):
        flags, values = _limiter_fields(limiter)[:3], _limiter_fields(limiter)[3:]
        assert flags == (False, False, False)
        assert all(math.isnan(v) for v in values)
    assert c.state_interface_configuration().names == ("l/position", "r/position")
    assert c.command_interface_configuration().names == ("l/velocity", "r/velocity")


def test_every_parameter_is_read_under_its_own_name() -> None:
    given = {
        "wheel_separation_multiplier": 1.5,
        "left_wheel_radius_multiplier": 0.9,
        "right_wheel_radius_multiplier": 1.1,
        "tf_frame_prefix_enable": False,
        "tf_frame_prefix": "robot",
        "odom_frame_id": "world",
        "base_frame_id": "chassis",
        "pose_covariance_diagonal": [1, 2, 3, 4, 5, 6],
        "twist_covariance_diagonal": [6, 5, 4, 3, 2, 1],
        "open_loop": True,
        "position_feedback": False,
        "enable_odom_tf": False,
        "cmd_vel_timeout": 0.25,
        "publish_limited_velocity": True,
        "velocity_rolling_window_size": 3,
        "use_stamped_vel": False,
        "publish_rate": 20.0,
        "cmd_vel_unstamped_topic": "/teleop",
    }
    c = _controller(**given)
    assert (
        c.wheel_separation_multiplier,
        c.left_wheel_radius_multiplier,
        c.right_wheel_radius_multiplier,
    ) == (1.5, 0.9, 1.1)
    assert (c.tf_frame_prefix_enable, c.tf_frame_prefix) == (False, "robot")
    assert (c.odom_frame_id, c.base_frame_id) == ("world", "chassis")
    assert c.pose_covariance_diagonal == [1.0, 2.0, 3.0, 4.0, 5.0, 6.0]
    assert c.twist_covariance_diagonal == [6.0, 5.0, 4.0, 3.0, 2.0, 1.0]
    assert (c.open_loop, c.position_feedback, c.enable_odom_tf) == (True, False, False)
    assert (c.cmd_vel_timeout_s, c.publish_rate_hz) == (0.25, 20.0)
    assert (c.publish_limited_velocity, c.use_stamped_vel) == (True, False)
    assert c.velocity_rolling_window_size == 3 == c.odometry.window
    assert c.unstamped_topic == "/teleop"
    assert c.state_interface_configuration().names == ("l/velocity", "r/velocity")


@pytest.mark.parametrize("axis", ["linear.x", "angular.z"])
def test_each_axis_reads_its_own_limits(axis: str) -> None:
    limits = {
        "has_velocity_limits": True, "has_acceleration_limits": True, "has_jerk_limits": True,
        "min_velocity": -1.0, "max_velocity": 2.0, "min_acceleration": -3.0,
        "max_acceleration": 4.0, "min_jerk": -5.0, "max_jerk": 6.0,
    }  # fmt: skip
    c = _controller(**{f"{axis}.{k}": v for k, v in limits.items()})
    ours, other = (
        (c.limiter_linear, c.limiter_angular)
        if axis == "linear.x"
        else (c.limiter_angular, c.limiter_linear)
    )
    assert _limiter_fields(ours) == tuple(limits.values())
    assert _limiter_fields(other)[:3] == (False, False, False)
    # a limit given as null (YAML ``~``) is NaN: the minimum then mirrors the maximum
    c = _controller(**{f"{axis}.max_velocity": 2.0, f"{axis}.min_velocity": None})
    limiter = c.limiter_linear if axis == "linear.x" else c.limiter_angular
    assert (limiter.min_velocity, limiter.max_velocity) == (-2.0, 2.0)


@pytest.mark.parametrize(
    ("params", "message"),
    [
        ({}, "controller 'dd': left_wheel_names and right_wheel_names are required"),
        (
            {"left_wheel_names": ["l"]},
            "controller 'dd': left_wheel_names and right_wheel_names are required",
        ),
        (
            {"right_wheel_names": ["r"]},
            "controller 'dd': left_wheel_names and right_wheel_names are required",
        ),
        (
            {**WHEEL_NAMES, "right_wheel_names": ["r", "r2"], **SIZES},
            "controller 'dd': the number of left wheels (1) and right wheels (2) differ",
        ),
        (
            {**WHEEL_NAMES, "wheel_radius": 0.1},
            "controller 'dd': wheel_separation and wheel_radius must be > 0",
        ),
        (
            {**WHEEL_NAMES, "wheel_separation": 0.5},
            "controller 'dd': wheel_separation and wheel_radius must be > 0",
        ),
        (
            {**WHEEL_NAMES, "wheel_separation": 0.5, "wheel_radius": -0.1},
            "controller 'dd': wheel_separation and wheel_radius must be > 0",
        ),
        (
            {**WHEEL_NAMES, **SIZES, "pose_covariance_diagonal": [0.0] * 5},
            "controller 'dd': pose_covariance_diagonal needs 6 values",
        ),
        (
            {**WHEEL_NAMES, **SIZES, "twist_covariance_diagonal": [0.0] * 7},
            "controller 'dd': twist_covariance_diagonal needs 6 values",
        ),
    ],
)
def test_bad_parameters_are_refused_with_what_is_wrong(
    params: dict[str, Any], message: str
) -> None:
    with pytest.raises(ControllerError) as refused:
        DiffDriveController().init("dd", params)
    assert str(refused.value) == message


def test_the_urdf_is_read_only_when_asked() -> None:
    """``derive_wheel_params_from_urdf`` defaults to off: without it, missing sizes are an
    error even when the robot would give them."""
    from tests.control.test_control_maths import DERIVED

    robot = load(
        DERIVED.format(joints=WHEEL.format(name="left_wheel") + WHEEL.format(name="right_wheel"))
    )
    names = {"left_wheel_names": ["left_wheel"], "right_wheel_names": ["right_wheel"]}
    with pytest.raises(ControllerError, match="must be > 0"):
        DiffDriveController().init("dd", names, robot=robot)
    c = DiffDriveController()
    c.init("dd", {**names, "derive_wheel_params_from_urdf": True}, robot=robot)
    assert c.wheel_radius == 0.08
    # without a robot, or with wheels the robot does not have, nothing is derived
    unknown = {"left_wheel_names": ["x"], "right_wheel_names": ["right_wheel"]}
    for robot_given, wheels in ((None, names), (robot, unknown)):
        params = {**wheels, "derive_wheel_params_from_urdf": True}
        with pytest.raises(ControllerError, match="must be > 0"):
            DiffDriveController().init("dd", params, robot=robot_given)


def test_a_refused_command_is_held_and_warned_at_powers_of_two(
    caplog: pytest.LogCaptureFixture,
) -> None:
    c = _controller()
    c.reset_commands()
    c.set_command(0.3, -0.2, 1.5)
    assert c.command == (0.3, -0.2, 1.5)
    caplog.set_level(logging.WARNING, "robomodel.control")
    bad = [(math.nan, 0.0), (0.0, math.inf), (MAX_TWIST * 2, 0.0), (0.0, -MAX_TWIST * 2)] * 2
    for linear, angular in bad:
        c.set_command(linear, angular, 2.0)
    assert c.command == (0.3, -0.2, 1.5)
    warnings = [r.getMessage() for r in caplog.records if r.name == "robomodel.control"]
    assert warnings == [
        "dd: cmd_vel (linear.x nan, angular.z 0.0) is not finite or beyond 1e+06; "
        "the last good command is held (1 times)",
        "dd: cmd_vel (linear.x 0.0, angular.z inf) is not finite or beyond 1e+06; "
        "the last good command is held (2 times)",
        "dd: cmd_vel (linear.x 0.0, angular.z -2000000.0) is not finite or beyond 1e+06; "
        "the last good command is held (4 times)",
        "dd: cmd_vel (linear.x 0.0, angular.z -2000000.0) is not finite or beyond 1e+06; "
        "the last good command is held (8 times)",
    ]
    # exactly the bound is taken; a stamp of zero or none is "now"
    c.set_command(MAX_TWIST, -MAX_TWIST, 3.0)
    assert c.command == (MAX_TWIST, -MAX_TWIST, 3.0)
    c._now_s = 7.25
    c.set_command(0.1, 0.0, 0.0)
    assert c.command == (0.1, 0.0, 7.25)
    c.set_command(0.2, 0.0)
    assert c.command == (0.2, 0.0, 7.25)
    # configuring again forgets the command and the refusals
    c.on_configure()
    assert c.command == (0.0, 0.0, -math.inf) and c._rejected == 0
    assert c.previous_commands == [(0.0, 0.0), (0.0, 0.0)]


@pytest.mark.parametrize(
    ("time_s", "stamp"),
    [
        (0.0, (0, 0)),
        (1.25, (1, 250_000_000)),
        (2.000000001, (2, 1)),
        (2.9999999999, (3, 0)),  # rounds up into the next second
        (-0.5, (-1, 500_000_000)),
    ],
)
def test_stamps_of_the_update_time(time_s: float, stamp: tuple[int, int]) -> None:
    assert _time(time_s) == Time(*stamp)


def _system(extra: str, update_hz: int = 100) -> tuple[Context, ControlSystem, Any]:
    ctx = Context("inproc", clock=ManualClock())
    robot = load(
        WHEELS.format(joints=WHEEL.format(name="left_wheel") + WHEEL.format(name="right_wheel"))
    )
    cfg = load_controller_config(
        "dd.yaml",
        text=f"controller_manager:\n  ros__parameters:\n    update_rate: {update_hz}\n"
        "    dd:\n      type: diff_drive_controller/DiffDriveController\n"
        "dd:\n  ros__parameters:\n    left_wheel_names: [left_wheel]\n"
        "    right_wheel_names: [right_wheel]\n    wheel_separation: 0.5\n"
        "    wheel_radius: 0.1\n" + extra,
    )
    system = ControlSystem.build(robot, cfg, context=ctx)
    return ctx, system, system.manager.entries["dd"].controller


def test_topics_queue_depths_and_the_limited_velocity() -> None:
    ctx, system, controller = _system(
        "    publish_limited_velocity: true\n    linear.x.has_acceleration_limits: true\n"
        "    linear.x.max_acceleration: 1.0\n    angular.z.has_velocity_limits: true\n"
        "    angular.z.max_velocity: 0.5\n    publish_rate: 10.0\n"
    )
    graph = ctx.graph()
    depth = {
        (name, kind): endpoint.qos.depth
        for name, info in graph.topics.items()
        for kind, endpoints in (("pub", info.publishers), ("sub", info.subscribers))
        for endpoint in endpoints
        if endpoint.node == "/dd" and name not in ("/rosout", "/parameter_events")
    }
    assert depth == {
        ("/dd/cmd_vel", "sub"): 10,
        ("/dd/odom", "pub"): 10,
        ("/tf", "pub"): 100,
        ("/dd/cmd_vel_out", "pub"): 10,
    }
    node = ctx.create_node("probe")
    limited: list[TwistStamped] = []
    odoms: list[OdometryMsg] = []
    node.create_subscription(TwistStamped, "/dd/cmd_vel_out", limited.append)
    node.create_subscription(OdometryMsg, "/dd/odom", odoms.append)
    for _ in range(50):
        controller.set_command(2.0, 3.0)
        ctx.advance(0.01)
        system.manager.step(0.01)
    ctx.spin_once()
    assert len(limited) == 50
    first, last = limited[0], limited[-1]
    # 1 m/s² from rest: 0.01 m/s after the first 10 ms; the turn rate clamped to 0.5 rad/s
    assert first.twist.linear.x == pytest.approx(0.01)
    assert first.twist.angular.z == 0.5
    assert last.twist.linear.x == pytest.approx(0.5)
    assert (first.twist.linear.y, first.twist.linear.z) == (0.0, 0.0)
    assert (first.twist.angular.x, first.twist.angular.y) == (0.0, 0.0)
    stamp = last.header.stamp
    assert (stamp.sec, stamp.nanosec) == (0, 500_000_000)
    assert len(odoms) == 4  # 10 Hz over 0.5 s: the first at 0.11 s, then each 0.1 s
    assert odoms[-1].header.stamp == Time(0, 410_000_000)
    ctx.shutdown()


def test_unstamped_commands_on_the_named_topic_and_no_tf_when_disabled() -> None:
    ctx, system, controller = _system(
        "    use_stamped_vel: false\n    cmd_vel_unstamped_topic: /teleop\n"
        "    enable_odom_tf: false\n    publish_rate: 0.0\n"
    )
    graph = ctx.graph()
    assert "/tf" not in graph.topics and "/dd/cmd_vel_out" not in graph.topics
    assert [(e.node, e.qos.depth) for e in graph.topics["/teleop"].subscribers] == [("/dd", 10)]
    node = ctx.create_node("probe")
    odoms: list[OdometryMsg] = []
    node.create_subscription(OdometryMsg, "/dd/odom", odoms.append)
    pub = node.create_publisher(Twist, "/teleop")
    for _ in range(5):
        pub.publish(Twist(Vector3(0.2, 0.0, 0.0), Vector3(0.0, 0.0, 0.4)))
        ctx.spin_once()
        ctx.advance(0.01)
        system.manager.step(0.01)
    ctx.spin_once()
    assert controller.command[:2] == (0.2, 0.4)
    assert len(odoms) == 4  # publish_rate 0: at every update after the first
    ctx.shutdown()


def test_cleanup_leaves_the_graph_and_deactivation_stops_the_wheels() -> None:
    ctx, system, controller = _system("    publish_limited_velocity: true\n")
    manager = system.manager
    controller.set_command(0.5, 0.0)
    for _ in range(3):
        ctx.advance(0.01)
        manager.step(0.01)
    wheels = list(controller.command_interfaces)
    assert wheels[0].get() == pytest.approx(5.0)
    manager.switch_controllers(deactivate=["dd"])
    assert [ci.get() for ci in wheels] == [0.0, 0.0]
    manager.cleanup_controller("dd")
    assert controller._subs == []
    assert (controller._odom_pub, controller._tf_pub, controller._limited_pub) == (None,) * 3
    topics = ctx.graph().topics
    made = ("/dd/cmd_vel", "/dd/odom", "/tf", "/dd/cmd_vel_out")
    assert not [name for name in made if name in topics]
    ctx.shutdown()


def test_velocity_feedback_and_open_loop_odometry() -> None:
    """Velocity feedback integrates each wheel's velocity times its radius over the period;
    open loop integrates the command, whatever the wheels do."""
    cm, ctrl, wheels = diff_drive_system(
        {**SIZES, "position_feedback": False, "left_wheel_radius_multiplier": 2.0}
    )
    ctrl.set_command(0.2, 0.0, 0.001)
    for _ in range(500):
        cm.step(0.001)
    # the left wheel is taken as twice as big: it turns half as fast for the same 0.2 m/s,
    # and the odometry still reads 0.2 m/s on each side
    assert wheels[0].get() == pytest.approx(1.0) and wheels[1].get() == pytest.approx(2.0)
    assert ctrl.odometry.linear == pytest.approx(0.2, abs=1e-3)
    assert ctrl.odometry.x == pytest.approx(0.1, abs=0.01)
    assert ctrl.odometry.heading == pytest.approx(0.0, abs=1e-9)

    cm, ctrl, wheels = diff_drive_system({**SIZES, "open_loop": True, "cmd_vel_timeout": 0.0})
    ctrl.set_command(0.0, 1.0, 0.001)
    for _ in range(500):
        cm.step(0.001)
    assert ctrl.odometry.angular == pytest.approx(1.0)
    assert ctrl.odometry.heading == pytest.approx(0.5, abs=0.01)


def test_a_wheel_reading_nan_stops_the_controller() -> None:
    from robomodel.control.controllers.base import ReturnType

    cm, ctrl, _ = diff_drive_system(SIZES)
    cm.step(0.001)
    assert ctrl.update(0.002, 0.001) is ReturnType.OK
    ctrl._right_state[0].set(math.nan)
    assert ctrl.update(0.003, 0.001) is ReturnType.ERROR


def test_an_inactive_controller_does_nothing() -> None:
    from robomodel.control.controllers.base import ReturnType

    c = _controller()
    c.on_configure()
    c.set_command(1.0, 0.0, 1.0)
    assert c.update(1.0, 0.01) is ReturnType.OK
    assert c._now_s == 0.0 and c.odometry.x == 0.0


def test_tf_and_odometry_carry_the_frames_and_the_pose() -> None:
    ctx, system, controller = _system(
        "    odom_frame_id: world\n    base_frame_id: chassis\n    tf_frame_prefix: robot\n"
        "    publish_rate: 100.0\n    cmd_vel_timeout: 0.0\n"
    )
    node = ctx.create_node("probe")
    tfs: list[TFMessage] = []
    odoms: list[OdometryMsg] = []
    node.create_subscription(TFMessage, "/tf", tfs.append)
    node.create_subscription(OdometryMsg, "/dd/odom", odoms.append)
    controller.set_command(0.3, 0.6, 0.001)
    for _ in range(100):
        ctx.advance(0.01)
        system.manager.step(0.01)
    ctx.spin_once()
    tf, odom = tfs[-1].transforms[0], odoms[-1]
    assert (tf.header.frame_id, tf.child_frame_id) == ("robot/world", "robot/chassis")
    assert (odom.header.frame_id, odom.child_frame_id) == ("robot/world", "robot/chassis")
    o = controller.odometry
    assert (odom.pose.pose.position.x, odom.pose.pose.position.y) == (o.x, o.y)
    assert o.y > 0.01  # turned left
    assert (tf.transform.translation.x, tf.transform.translation.y) == (o.x, o.y)
    assert tf.transform.translation.z == 0.0
    assert odom.pose.pose.orientation.z == pytest.approx(math.sin(o.heading / 2))
    assert odom.twist.twist.linear.x == o.linear and odom.twist.twist.angular.z == o.angular
    ctx.shutdown()


def test_the_stamped_command_s_own_stamp_is_kept() -> None:
    ctx, _, controller = _system("")
    node = ctx.create_node("probe")
    pub = node.create_publisher(TwistStamped, "/dd/cmd_vel")
    msg = TwistStamped()
    msg.header.stamp = Time(3, 500_000_000)
    msg.twist.linear.x, msg.twist.angular.z = 0.4, -0.1
    pub.publish(msg)
    ctx.spin_once()
    assert controller.command == (0.4, -0.1, 3.5)
    ctx.shutdown()


def test_a_command_times_out_only_once_older_than_the_timeout() -> None:
    """humble: ``age_of_last_command > cmd_vel_timeout``; the held command is then zero."""
    cm, ctrl, wheels = diff_drive_system(SIZES)
    cm.step(0.001)
    ctrl.set_command(0.5, 0.0, 1.0)
    ctrl.update(1.5, 0.001)  # exactly 0.5 s old: still driving
    assert ctrl.command == (0.5, 0.0, 1.0) and wheels[0].get() == pytest.approx(5.0)
    ctrl.update(1.5005, 0.0005)
    assert ctrl.command == (0.0, 0.0, 1.0) and wheels[0].get() == 0.0


def test_a_refusal_before_configuring_is_the_first() -> None:
    c = _controller()
    assert c._rejected == 0
    c.set_command(math.nan, 0.0)
    assert c._rejected == 1


def test_skid_steer_odometry_is_the_mean_of_each_side() -> None:
    cm, ctrl, _wheels = diff_drive_system({**SIZES, "cmd_vel_timeout": 0.0}, wheels_per_side=2)
    ctrl.set_command(0.3, 0.0, 0.001)
    for _ in range(300):
        cm.step(0.001)
    assert ctrl.odometry.linear == pytest.approx(0.3, rel=1e-3)
    assert ctrl.odometry.heading == pytest.approx(0.0, abs=1e-9)


def test_a_publish_rate_below_one_hertz_is_kept() -> None:
    ctx, system, _ = _system("    publish_rate: 0.5\n    cmd_vel_timeout: 0.0\n", update_hz=10)
    node = ctx.create_node("probe")
    odoms: list[OdometryMsg] = []
    node.create_subscription(OdometryMsg, "/dd/odom", odoms.append)
    for _ in range(45):  # 4.5 s: every 2 s after the first update
        ctx.advance(0.1)
        system.manager.step(0.1)
    ctx.spin_once()
    assert len(odoms) == 2
    ctx.shutdown()


def test_angular_jerk_limits_use_the_two_commands_before() -> None:
    cm, ctrl, _ = diff_drive_system(
        {**SIZES, "cmd_vel_timeout": 0.0, "angular.z.has_jerk_limits": True,
         "angular.z.max_jerk": 10.0}
    )  # fmt: skip
    ctrl.set_command(0.0, 1.0, 0.001)
    expected = SpeedLimiter(has_jerk_limits=True, max_jerk=10.0)
    older, previous = 0.0, 0.0
    for _ in range(5):
        cm.step(0.001)
        want = expected.limit(1.0, previous, older, 0.001)
        older, previous = previous, want
        assert ctrl.previous_commands[1][1] == pytest.approx(want)
    assert 0.0 < previous < 1.0
