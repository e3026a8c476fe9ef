"""Controller behaviour: JSB, diff drive (timeout, skid steer, odometry topic), JTC, PID on mock."""

from __future__ import annotations

import math

import numpy as np
import pytest

from robomodel.control import ControlSystem, load_controller_config
from robomodel.control.controllers import GoalStatus, JointTrajectoryController
from robomodel.runtime import Context
from robomodel.runtime.clock import ManualClock
from robomodel.runtime.msg import (
    Duration,
    Float64,
    Float64MultiArray,
    JointState,
    JointTrajectory,
    JointTrajectoryPoint,
    Odometry,
    TFMessage,
    TwistStamped,
)
from tests.conftest import EXAMPLES
from tests.control.helpers import arm, arm_manager, diff_drive_system

JTC = "joint_trajectory_controller/JointTrajectoryController"


def _example_system(package: str, urdf: str, config: str) -> tuple[Context, ControlSystem]:
    """An example robot's ``urdf/<urdf>`` with ``config/<config>`` on a fresh in-process bus."""
    from robomodel.loading import load

    robot = load(EXAMPLES / package / "urdf" / urdf)
    ctx = Context("inproc", clock=ManualClock())
    return ctx, ControlSystem.build(robot, EXAMPLES / package / "config" / config, context=ctx)  # type: ignore[arg-type]


def test_cmd_vel_timeout_stops_the_robot() -> None:
    cm, ctrl, wheels = diff_drive_system({"wheel_radius": 0.1, "wheel_separation": 0.5})
    ctrl.set_command(1.0, 0.0, 0.001)
    for _ in range(400):
        cm.step(0.001)
    assert wheels[0].get() == pytest.approx(10.0)
    for _ in range(200):  # the command is 0.5 s old after ~500 updates
        cm.step(0.001)
    assert wheels[0].get() == 0.0 and wheels[1].get() == 0.0


def test_zero_cmd_vel_timeout_disables_it_and_skid_steer_drives_all_wheels() -> None:
    cm, ctrl, wheels = diff_drive_system(
        {"wheel_radius": 0.1, "wheel_separation": 0.5, "cmd_vel_timeout": 0.0}, wheels_per_side=2
    )
    ctrl.set_command(0.5, 1.0, 0.001)
    for _ in range(2000):
        cm.step(0.001)
    left, right = (0.5 - 1.0 * 0.25) / 0.1, (0.5 + 1.0 * 0.25) / 0.1
    assert [w.get() for w in wheels] == pytest.approx([left, right, left, right])


def test_diff_drive_odometry_topics_covariances_and_tf() -> None:
    ctx = Context("inproc", clock=ManualClock())
    from robomodel.loading import load
    from tests.control.helpers import WHEEL, WHEELS

    robot = load(
        WHEELS.format(joints=WHEEL.format(name="left_wheel") + WHEEL.format(name="right_wheel"))
    )
    cfg = load_controller_config(
        "dd.yaml",
        text="""
controller_manager:
  ros__parameters:
    update_rate: 100
    dd:
      type: diff_drive_controller/DiffDriveController
dd:
  ros__parameters:
    left_wheel_names: [left_wheel]
    right_wheel_names: [right_wheel]
    wheel_separation: 0.5
    wheel_radius: 0.1
    pose_covariance_diagonal: [0.001, 0.001, 1000000.0, 1000000.0, 1000000.0, 1000.0]
    twist_covariance_diagonal: [0.001, 0.001, 1000000.0, 1000000.0, 1000000.0, 1000.0]
""",
    )
    system = ControlSystem.build(robot, cfg, context=ctx)  # type: ignore[arg-type]
    node = ctx.create_node("probe")
    odoms: list[Odometry] = []
    tfs: list[TFMessage] = []
    node.create_subscription(Odometry, "/dd/odom", odoms.append)
    node.create_subscription(TFMessage, "/tf", tfs.append)
    pub = node.create_publisher(TwistStamped, "/dd/cmd_vel")
    for _ in range(100):
        msg = TwistStamped()
        msg.twist.linear.x = 0.2  # zero stamp: replaced by "now"
        pub.publish(msg)
        ctx.advance(0.01)
        system.manager.step(0.01)
    ctx.spin_once()
    assert len(odoms) in (49, 50)  # publish_rate 50 Hz at a 100 Hz update rate
    last = odoms[-1]
    assert last.header.frame_id == "odom" and last.child_frame_id == "base_link"
    assert last.pose.covariance[0] == 0.001 and last.pose.covariance[35] == 1000.0
    assert last.twist.covariance[14] == 1000000.0
    # the mock integrates the wheel velocity commands, so the odometry sees ~0.2 m/s
    assert last.pose.pose.position.x == pytest.approx(0.2 * 0.98, abs=0.01)
    assert last.twist.twist.linear.x == pytest.approx(0.2, abs=1e-6)
    assert tfs[-1].transforms[0].child_frame_id == "base_link"
    ctx.shutdown()


def _trajectory(points: list[tuple[float, list[float]]], names: list[str]) -> JointTrajectory:
    msg = JointTrajectory(joint_names=names)
    for t, pos in points:
        sec = int(t)
        msg.points.append(
            JointTrajectoryPoint(positions=pos, time_from_start=Duration(sec, int((t - sec) * 1e9)))
        )
    return msg


def _jtc(
    params: dict[str, object], context: Context | None = None
) -> tuple[object, JointTrajectoryController]:
    cm = arm_manager(context=context)
    cm.load_controller(
        "jtc",
        JTC,
        {
            "joints": ["joint1", "joint2"],
            "command_interfaces": ["position"],
            "state_interfaces": ["position", "velocity"],
            **params,
        },
    )
    cm.spawn(["jtc"])
    ctrl = cm.entries["jtc"].controller
    assert isinstance(ctrl, JointTrajectoryController)
    return cm, ctrl


def test_jtc_follows_and_succeeds() -> None:
    cm, ctrl = _jtc({"constraints.joint1.goal": 0.01, "constraints.joint2.goal": 0.01})
    goal = ctrl.send_goal(_trajectory([(1.0, [0.5, -0.5])], ["joint1", "joint2"]))
    for _ in range(50):
        cm.step()  # type: ignore[attr-defined]
    # from the initial 0.25 (initial_value) linearly to 0.5 over 1 s
    assert cm.resources.commands.values[0] == pytest.approx(0.25 + 0.25 * 0.5, abs=0.01)  # type: ignore[attr-defined]
    assert goal.status is GoalStatus.ACTIVE
    for _ in range(60):
        cm.step()  # type: ignore[attr-defined]
    assert goal.status is GoalStatus.SUCCEEDED


def test_jtc_snapshot_is_a_frozen_copy_of_the_last_update() -> None:
    """What the action and services read: the state at the last update, which they cannot
    change, and nothing measured while the controller is inactive."""
    import dataclasses

    cm, ctrl = _jtc({})
    goal = ctrl.send_goal(_trajectory([(1.0, [0.5, -0.5])], ["joint1", "joint2"]))
    for _ in range(50):
        cm.step()  # type: ignore[attr-defined]
    state = ctrl.snapshot()
    assert state.active and state.goal is goal and state.trajectory is ctrl.trajectory
    assert state.joints == ("joint1", "joint2")
    assert state.time_s == pytest.approx(0.5, abs=1e-9)  # the 50th update of a 100 Hz loop
    # written at 0.49 s into the trajectory: 0.25 -> 0.5 and 0 -> -0.5 linearly over 1 s
    assert state.commands["position"] == pytest.approx((0.3725, -0.245), abs=1e-9)
    assert state.positions[0] == pytest.approx(0.25 + 0.25 * 0.48, abs=0.01)
    with pytest.raises(dataclasses.FrozenInstanceError):
        state.time_s = 0.0  # type: ignore[misc]
    with pytest.raises(TypeError):
        state.commands["position"] = (0.0, 0.0)  # type: ignore[index]
    cm.step()  # type: ignore[attr-defined]
    assert state.time_s == pytest.approx(0.5, abs=1e-9)  # a copy: later updates leave it
    cm.switch_controllers(deactivate=["jtc"])  # type: ignore[attr-defined]
    inactive = ctrl.snapshot()
    assert not inactive.active and inactive.positions == () and inactive.commands == {}


def test_jtc_path_tolerance_aborts_and_holds() -> None:
    cm, ctrl = _jtc({"constraints.joint1.trajectory": 0.05})
    # mock hardware follows position commands, so force a tracking error via the offset hardware
    goal = ctrl.send_goal(
        _trajectory([(1.0, [1.0, 0.0])], ["joint1", "joint2"]),
        path_tolerance={"joint1": 0.001},
    )
    cm.step()  # type: ignore[attr-defined]
    cm.step()  # type: ignore[attr-defined]
    # mock state lags one cycle behind the command: error ~0.0075 rad > 0.001
    assert goal.status is GoalStatus.ABORTED and goal.error_code == -4


def test_jtc_goal_tolerance_aborts_after_goal_time() -> None:
    cm, ctrl = _jtc({"constraints.goal_time": 0.2, "constraints.joint2.goal": 0.001})
    rm = cm.resources  # type: ignore[attr-defined]
    goal = ctrl.send_goal(_trajectory([(0.5, [0.3, 0.4])], ["joint1", "joint2"]))
    slot = rm.commands.slot("joint2/position")
    for _ in range(100):
        cm.step()  # type: ignore[attr-defined]
        rm.commands.values[slot] = 0.0  # a stuck joint: the hardware never gets there
    assert goal.status is GoalStatus.ABORTED and goal.error_code == -5


def test_jtc_new_trajectory_replaces_and_cancels_goal() -> None:
    cm, ctrl = _jtc({})
    first = ctrl.send_goal(_trajectory([(2.0, [1.0, 1.0])], ["joint1", "joint2"]))
    cm.step()  # type: ignore[attr-defined]
    second = ctrl.send_goal(_trajectory([(1.0, [-1.0, -1.0])], ["joint1", "joint2"]))
    cm.step()  # type: ignore[attr-defined]
    assert first.status is GoalStatus.CANCELED
    for _ in range(150):
        cm.step()  # type: ignore[attr-defined]
    assert second.status is GoalStatus.SUCCEEDED
    assert cm.resources.commands.values[0] == pytest.approx(-1.0)  # type: ignore[attr-defined]


def test_jtc_rejects_invalid_trajectories() -> None:
    _, ctrl = _jtc({"allow_nonzero_velocity_at_trajectory_end": False})
    bad = _trajectory([(1.0, [0.0, 0.0]), (0.5, [0.0, 0.0])], ["joint1", "joint2"])
    assert ctrl.send_goal(bad).status is GoalStatus.ABORTED
    assert not ctrl.send_trajectory(_trajectory([(1.0, [0.0])], ["joint1"]))  # partial
    assert not ctrl.send_trajectory(_trajectory([(1.0, [0.0, 0.0])], ["joint1", "nope"]))
    end_vel = _trajectory([(1.0, [0.0, 0.0])], ["joint1", "joint2"])
    end_vel.points[0].velocities = [1.0, 0.0]
    assert not ctrl.send_trajectory(end_vel)


def test_rrbot_ros1_pid_over_topics_moves_joint1() -> None:
    """Seed 000: ROS 1 YAML + ROS 1 transmissions; publish 1.5 on .../command."""

    ctx, system = _example_system("rrbot_description", "rrbot.xacro", "rrbot_control.yaml")
    node = ctx.create_node("probe")
    states: list[JointState] = []
    node.create_subscription(JointState, "/joint_states", states.append)
    node.create_publisher(Float64, "/joint1_position_controller/command").publish(Float64(1.5))
    for _ in range(500):
        ctx.advance(0.01)
        system.manager.step(0.01)
    ctx.spin_once()
    assert states and states[-1].name == ["joint1", "joint2"]
    assert states[-1].position[0] == pytest.approx(1.5, abs=0.3)  # PD with gravity: offset
    ctx.shutdown()


def test_group_position_controller_two_link_arm() -> None:
    """Seed 003: joint1_position_controller of type JointGroupPositionController."""

    ctx, system = _example_system(
        "two_link_arm", "two_link_arm.urdf.xacro", "position_controllers.yaml"
    )
    node = ctx.create_node("probe")
    node.create_publisher(Float64MultiArray, "/joint1_position_controller/commands").publish(
        Float64MultiArray(data=[1.0])
    )
    for _ in range(3):
        ctx.advance(0.01)
        system.manager.step(0.01)
    rm = system.resources
    assert rm.states.values[rm.states.slot("joint1/position")] == 1.0
    ctx.shutdown()


def test_gravity_compensation_holds_the_arm() -> None:
    from robomodel.loading import load

    robot = load(EXAMPLES / "rrbot_description" / "urdf" / "rrbot.xacro")
    cfg = load_controller_config(
        "g.yaml",
        text="gc: {type: robomodel_controllers/GravityCompensationController, kd: 2.0}\n",
    )
    system = ControlSystem.build(robot, cfg)  # type: ignore[arg-type]
    rm = system.resources
    rm.states.values[rm.states.slot("joint1/position")] = 0.7  # tilt it, then let go
    for _ in range(300):
        system.manager.step(0.01)
    # only the first cycle (no command yet) lets it sag; then g(q) holds it still
    assert rm.states.values[rm.states.slot("joint1/position")] == pytest.approx(0.7, abs=0.05)
    assert rm.states.values[rm.states.slot("joint1/velocity")] == pytest.approx(0.0, abs=0.01)
    assert not math.isnan(rm.commands.values[0])
    assert arm().name == "arm"


def test_jtc_effort_pid_mode_moves_rrbot_on_mock_dynamics() -> None:
    from robomodel.loading import load

    robot = load(EXAMPLES / "rrbot_description" / "urdf" / "rrbot.xacro")
    cfg = load_controller_config(
        "j.yaml",
        text="""
arm:
  type: effort_controllers/JointTrajectoryController
  joints: [joint1, joint2]
  gains:
    joint1: {p: 200.0, d: 20.0, i: 0.0}
    joint2: {p: 100.0, d: 10.0, i: 0.0}
  constraints: {goal_time: 2.0, joint1: {goal: 0.1}, joint2: {goal: 0.1}}
""",
    )
    system = ControlSystem.build(robot, cfg)  # type: ignore[arg-type]
    ctrl = system.manager.entries["arm"].controller
    assert isinstance(ctrl, JointTrajectoryController)
    assert ctrl.use_pid and ctrl.command_kinds == ("effort",)
    goal = ctrl.send_goal(_trajectory([(1.0, [0.5, -0.3])], ["joint1", "joint2"]))
    for _ in range(250):
        system.manager.step(0.01)
    rm = system.resources
    assert goal.status is GoalStatus.SUCCEEDED, goal.error_string
    assert rm.states.values[rm.states.slot("joint1/position")] == pytest.approx(0.5, abs=0.1)


def test_jtc_angle_wraparound_and_cmd_timeout() -> None:
    cm, ctrl = _jtc({"gains.joint1.angle_wraparound": True, "cmd_timeout": 0.1})
    assert ctrl.wraparound == [True, False]
    ctrl.send_trajectory(_trajectory([(0.2, [0.4, 0.4])], ["joint1", "joint2"]))
    for _ in range(40):
        cm.step()  # type: ignore[attr-defined]
    assert ctrl._holding  # held after end + cmd_timeout


@pytest.mark.parametrize(
    ("enable", "prefix", "namespace", "odom"),
    [
        (True, "", "/", "odom"),
        (True, "robot", "/", "robot/odom"),
        (True, "", "/ns", "ns/odom"),
        (False, "robot", "/ns", "odom"),
    ],
)
def test_diff_drive_tf_frame_prefix(enable: bool, prefix: str, namespace: str, odom: str) -> None:
    from robomodel.control.controllers import DiffDriveController

    ctx = Context("inproc", clock=ManualClock())
    node = ctx.create_node("dd", namespace)
    c = DiffDriveController()
    c.init(
        "dd",
        {
            "left_wheel_names": ["l"],
            "right_wheel_names": ["r"],
            "wheel_separation": 1.0,
            "wheel_radius": 0.1,
            "tf_frame_prefix_enable": enable,
            "tf_frame_prefix": prefix,
        },
        node=node,
    )
    assert c.frame_prefix + c.odom_frame_id == odom
    ctx.shutdown()


def test_diff_drive_rejects_bad_parameters() -> None:
    from robomodel.control.controllers import ControllerError, DiffDriveController

    for params in (
        {},
        {"left_wheel_names": ["l"]},
        {
            "left_wheel_names": ["l"],
            "right_wheel_names": ["r", "r2"],
            "wheel_separation": 1,
            "wheel_radius": 1,
        },
        {
            "left_wheel_names": ["l"],
            "right_wheel_names": ["r"],
            "wheel_separation": 0,
            "wheel_radius": 1,
        },
    ):
        with pytest.raises(ControllerError):
            DiffDriveController().init("dd", params)


def test_jsb_dynamic_joint_states_and_pid_state_topic() -> None:
    from robomodel.runtime.msg import DynamicJointState, JointControllerState

    ctx, system = _example_system("rrbot_description", "rrbot.xacro", "rrbot_control.yaml")
    system.manager.load_controller("jsb", "joint_state_broadcaster/JointStateBroadcaster")
    system.manager.spawn(["jsb"])  # ROS 2's broadcaster: also /dynamic_joint_states (Humble)
    node = ctx.create_node("probe")
    dyn: list[DynamicJointState] = []
    pid_state: list[JointControllerState] = []
    node.create_subscription(DynamicJointState, "/dynamic_joint_states", dyn.append)
    node.create_subscription(
        JointControllerState, "/joint1_position_controller/state", pid_state.append
    )
    for _ in range(20):
        system.manager.step(0.01)
    ctx.spin_once()
    assert dyn[-1].joint_names == ["joint1", "joint2"]
    assert dyn[-1].interface_values[0].interface_names == ["position", "velocity", "effort"]
    assert len(pid_state) == 2  # every 10th update, as ROS 1
    assert pid_state[-1].p == 100.0 and pid_state[-1].time_step == 0.01
    ctx.shutdown()


SEED_000 = """\
rrbot:
  # Publish all joint states
  joint_state_controller:
    type: joint_state_controller/JointStateController
    publish_rate: 50
  # Position controllers
  joint1_position_controller:
    type: effort_controllers/JointPositionController
    joint: joint1
    pid: {p: 100.0, I: 0.01, d: 10.0}
"""


def test_seed_000_namespaced_file(caplog: pytest.LogCaptureFixture) -> None:
    """The seed's file nests everything under rrbot: topics live in /rrbot, as in ROS 1."""
    from robomodel.loading import load

    robot = load(EXAMPLES / "rrbot_description" / "urdf" / "rrbot.xacro")
    ctx = Context("inproc", clock=ManualClock())
    with caplog.at_level("WARNING", logger="robomodel.control"):
        system = ControlSystem.build(
            robot,  # type: ignore[arg-type]
            load_controller_config("rrbot_control.yaml", text=SEED_000),
            context=ctx,
        )
    assert any("'pid.I' is ignored" in r.message and "pid.i" in r.message for r in caplog.records)
    assert system.manager.service_prefix == "/rrbot/controller_manager"
    node = ctx.create_node("probe")
    states: list[JointState] = []
    node.create_subscription(JointState, "/rrbot/joint_states", states.append)
    node.create_publisher(Float64, "/rrbot/joint1_position_controller/command").publish(
        Float64(1.5)
    )
    for _ in range(300):
        ctx.advance(0.01)
        system.manager.step(0.01)
    ctx.spin_once()
    assert states[-1].position[0] == pytest.approx(1.6, abs=0.2)
    from robomodel.runtime.msg.types.controller_manager_msgs import ListControllers

    answer = ctx.call_service("/rrbot/controller_manager/list_controllers", ListControllers)
    assert [c.state for c in answer.controller] == ["active", "active"]
    ctx.shutdown()


def test_seed_001_ur5_position_controllers() -> None:

    ctx, system = _example_system("ur5_description", "ur5.urdf.xacro", "ur5_controllers.yaml")
    node = ctx.create_node("probe")
    node.create_publisher(Float64, "/joint2_position_controller/command").publish(Float64(-1.2))
    for _ in range(3):
        ctx.advance(0.01)
        system.manager.step(0.01)
    rm = system.resources
    assert rm.states.values[rm.states.slot("shoulder_lift_joint/position")] == -1.2
    assert rm.states.values[rm.states.slot("shoulder_pan_joint/position")] == 0.0
    ctx.shutdown()


def test_seed_002_simplebot_drives_in_a_circle() -> None:
    from robomodel.runtime.msg import Twist

    ctx, system = _example_system(
        "simplebot_description", "simplebot.urdf.xacro", "simplebot_controllers.yaml"
    )
    node = ctx.create_node("probe")
    odoms: list[Odometry] = []
    node.create_subscription(Odometry, "/simplebot_controller/odom", odoms.append)
    pub = node.create_publisher(Twist, "/simplebot_controller/cmd_vel")  # ROS 1: unstamped
    for _ in range(int(math.pi / 0.5 / 0.01)):  # half a turn at 0.5 rad/s
        msg = Twist()
        msg.linear.x = 0.3
        msg.angular.z = 0.5
        pub.publish(msg)
        ctx.advance(0.01)
        system.manager.step(0.01)
    ctx.spin_once()
    pose = odoms[-1].pose.pose
    # a half circle of radius v/ω = 0.6 m: x back near 0, y near 1.2 m
    assert pose.position.x == pytest.approx(0.0, abs=0.03)
    assert pose.position.y == pytest.approx(1.2, abs=0.03)
    assert odoms[-1].pose.covariance[35] == 1000.0
    ctx.shutdown()


def test_jtc_follow_joint_trajectory_action_and_query_state() -> None:
    """FollowJointTrajectory over rcl_action's services and topics, QueryTrajectoryState."""
    from robomodel.runtime.action_client import ActionClient
    from robomodel.runtime.msg import JointTrajectory, message_from_dict
    from robomodel.runtime.msg.types.action_msgs import GoalStatus, GoalStatusArray
    from robomodel.runtime.msg.types.builtin_interfaces import Time
    from robomodel.runtime.msg.types.control_msgs import (
        FollowJointTrajectory,
        QueryTrajectoryState,
        QueryTrajectoryState_Request,
    )

    ctx = Context("inproc", clock=ManualClock())
    cm, ctrl = _jtc({"constraints.joint1.goal": 0.01}, context=ctx)
    graph = ctx.graph()
    base = "/jtc/follow_joint_trajectory/_action"
    assert {f"{base}/send_goal", f"{base}/cancel_goal", f"{base}/get_result"} <= set(graph.services)
    assert {f"{base}/feedback", f"{base}/status"} <= set(graph.topics)
    statuses: list[GoalStatusArray] = []
    ctx.create_node("probe").create_subscription(GoalStatusArray, f"{base}/status", statuses.append)

    def goal(
        points: list[dict[str, object]], joints: tuple[str, ...] = ("joint1", "joint2")
    ) -> object:
        trajectory = message_from_dict(
            JointTrajectory, {"joint_names": list(joints), "points": points}
        )
        return FollowJointTrajectory.Goal(trajectory=trajectory)

    def run(cycles: int) -> None:
        for _ in range(cycles):
            cm.step()  # type: ignore[attr-defined]
            ctx.advance(0.01)

    client = ActionClient(ctx, FollowJointTrajectory, "/jtc/follow_joint_trajectory")
    goal_id, accepted = client.send_goal(
        goal([{"positions": [0.6, 0.1], "time_from_start": {"sec": 1}}])
    )
    assert accepted
    run(1)
    start = ctrl.trajectory.start_s  # type: ignore[union-attr]

    def query(t: float) -> object:
        request = QueryTrajectoryState_Request(Time.from_seconds(t))
        return ctx.call_service("/jtc/query_state", QueryTrajectoryState, request)

    mid = query(start + 0.5)
    assert mid.success and mid.name == ["joint1", "joint2"]  # type: ignore[attr-defined]
    # linear from the measured (0.25, 0) at reception to (0.6, 0.1) at 1 s
    assert mid.position == pytest.approx([0.25 + 0.35 * 0.5, 0.05], abs=0.02)  # type: ignore[attr-defined]
    late = query(start + 5.0)
    assert not late.success and "after the current trajectory end" in late.message  # type: ignore[attr-defined]
    assert late.position == pytest.approx([0.6, 0.1])  # type: ignore[attr-defined]
    assert "earlier than the current trajectory start" in query(0.0).message  # type: ignore[attr-defined]
    run(120)
    status, result = client.get_result(goal_id)
    assert status == GoalStatus.STATUS_SUCCEEDED and result.error_code == 0
    assert statuses and statuses[-1].status_list[-1].status == GoalStatus.STATUS_SUCCEEDED
    second, _ = client.send_goal(goal([{"positions": [0.0, 0.0], "time_from_start": {"sec": 2}}]))
    run(2)
    canceling = client.cancel(second)
    assert canceling.return_code == 0 and canceling.goals_canceling[0].goal_id == second
    run(1)
    assert client.get_result(second)[0] == GoalStatus.STATUS_CANCELED
    assert client.cancel(second).return_code == 3  # ERROR_GOAL_TERMINATED
    _, rejected = client.send_goal(goal([{"positions": [1.0]}], ("x",)))
    assert not rejected  # validation fails: rejected, as Humble's goal_received_callback
    cm.switch_controllers(deactivate=["jtc"])  # type: ignore[attr-defined]
    assert query(0.0).message.endswith("not active.")  # type: ignore[attr-defined]
    ctx.shutdown()


def test_jtc_goal_waits_for_the_joint_to_stop() -> None:
    cm, ctrl = _jtc({"constraints.stopped_velocity_tolerance": 0.01})
    rm = cm.resources  # type: ignore[attr-defined]
    goal = ctrl.send_goal(_trajectory([(0.2, [0.3, 0.3])], ["joint1", "joint2"]))
    vel = rm.states.slot("joint1/velocity")
    for _ in range(40):
        cm.step()  # type: ignore[attr-defined]
        rm.states.values[vel] = 0.5  # still moving after the end
    assert goal.status is GoalStatus.ACTIVE
    rm.states.values[vel] = 0.0
    rm.commands.values[rm.commands.slot("joint1/velocity")] = 0.0  # the mock mirrors it
    cm.step()  # type: ignore[attr-defined]
    assert goal.status is GoalStatus.SUCCEEDED


def test_pid_gains_set_through_the_parameter_service_apply_live() -> None:
    """dynamic_reconfigure for the PID: a set of pid.p changes the running controller."""
    from robomodel.runtime.msg import JointControllerState

    ctx, system = _example_system("rrbot_description", "rrbot.xacro", "rrbot_control.yaml")
    controller = system.manager.entries["joint1_position_controller"].controller
    node = ctx.create_node("probe")
    pid_state: list[JointControllerState] = []
    node.create_subscription(
        JointControllerState, "/joint1_position_controller/state", pid_state.append
    )
    from robomodel.runtime.param_client import ParameterClient

    params = ParameterClient(ctx, "/joint1_position_controller")
    assert params.set_atomically({"pid.p": 12.5, "pid.d": 0.5}).successful
    assert controller.pid.gains.p == 12.5 and controller.pid.gains.d == 0.5  # type: ignore[attr-defined]
    for _ in range(10):
        system.manager.step(0.01)
    ctx.spin_once()
    assert pid_state[-1].p == 12.5 and pid_state[-1].d == 0.5
    [refused] = params.set({"pid.i": "fast"})
    assert not refused.successful and "pid.i" in refused.reason  # a double stays one
    # A gain not in the file yet is new to the node; the controller refuses a non-number.
    [refused] = params.set({"pid.i_clamp": "wide"})
    assert not refused.successful and "'pid.i_clamp' must be a number" in refused.reason
    assert params.set({"pid.i_clamp": 2.0})[0].successful
    assert controller.pid.gains.i_max == 2.0 and controller.pid.gains.i_min == -2.0  # type: ignore[attr-defined]
    assert controller.pid.gains.i == pytest.approx(0.01)  # type: ignore[attr-defined]
    assert params.set({"joint": "joint1"})[0].successful  # not a gain: no PID change, no refusal
    ctx.shutdown()


def test_jtc_publishes_controller_state_at_every_update_or_the_state_rate() -> None:
    """Jazzy: ~/controller_state at every update (control_msgs 5 layout, speed scaling 1);
    a Humble YAML's state_publish_rate still throttles it; no legacy ~/state."""
    from robomodel.runtime.msg import JointTrajectoryControllerState

    for params, expected, spacing_s in (({}, 50, 0.01), ({"state_publish_rate": 25.0}, 13, 0.04)):
        ctx = Context("inproc", clock=ManualClock())
        cm, ctrl = _jtc(params, context=ctx)
        probe = ctx.create_node("probe")
        states: list[JointTrajectoryControllerState] = []
        legacy: list[JointTrajectoryControllerState] = []
        probe.create_subscription(
            JointTrajectoryControllerState, "/jtc/controller_state", states.append
        )
        probe.create_subscription(JointTrajectoryControllerState, "/jtc/state", legacy.append)
        ctrl.send_trajectory(_trajectory([(1.0, [0.5, -0.5])], ["joint1", "joint2"]))
        period = 1.0 / cm.update_rate_hz
        for _ in range(round(0.5 / period)):
            cm.step()
            ctx.spin_once(0.0)
        stamps = [m.header.stamp.sec + m.header.stamp.nanosec * 1e-9 for m in states]
        assert len(states) == expected and legacy == []  # 0.5 s of 100 Hz updates
        assert np.diff(stamps) == pytest.approx([spacing_s] * (expected - 1))
        last = states[-1]
        assert last.joint_names == ["joint1", "joint2"] and last.speed_scaling_factor == 1.0
        # reference: the linear ramp from 0.25 (initial_value) to the waypoint, sampled
        assert last.reference.positions[0] == pytest.approx(0.25 + 0.25 * stamps[-1], abs=0.02)
        assert last.output.positions == last.reference.positions  # position commands forward it
        measured = [rm.get() for rm in ctrl.state_interfaces[:2]]  # positions after the write
        assert len(last.feedback.positions) == 2 and len(last.feedback.velocities) == 2
        assert last.error.positions == pytest.approx(
            [r - f for r, f in zip(last.reference.positions, last.feedback.positions, strict=True)]
        )
        assert measured[0] == pytest.approx(last.reference.positions[0], abs=0.02)
        ctx.shutdown()
