"""The five numeric reference scenarios of the notes (§2.8), from the upstream tests."""

from __future__ import annotations

import math

import pytest

from robomodel.control import AntiWindup, Gains, Pid, PidKilted
from robomodel.control.controllers import Odometry, RollingMean, Trajectory, TrajectoryPoint
from robomodel.control.transmissions import DifferentialTransmission, SimpleTransmission
from tests.control.helpers import diff_drive_system

P = TrajectoryPoint


def _odom(sep: float = 1.0, r: float = 1.0) -> Odometry:
    o = Odometry(10)
    o.set_wheel_params(sep, r, r)
    o.init(0.0)
    return o


def test_odometry_exact_arc_rotation_open_loop_and_small_dt() -> None:
    o = _odom()
    assert o.update_from_velocity(1.0, 2.0, 1.0)
    assert (o.x, o.y, o.heading) == pytest.approx((1.262206, 0.689547, 1.0), abs=1e-6)
    o = _odom()
    o.update_from_velocity(-1.0, 1.0, 1.0)
    assert (o.x, o.y, o.heading) == pytest.approx((0.0, 0.0, 2.0), abs=1e-12)
    o = _odom()
    o.update_open_loop(2.0, 0.5, 1.0)
    assert (o.x, o.y) == pytest.approx((1.917702, 0.489670), abs=1e-6)
    o = _odom()
    assert not o.update(1.0, 1.0, 1e-7)  # dt < 1e-4 rejected
    assert (o.x, o.y, o.heading) == (0.0, 0.0, 0.0)


def test_diff_drive_circle_and_rolling_mean() -> None:
    o = Odometry(10)
    o.set_wheel_params(0.5, 0.1, 0.1)
    o.init(0.0)
    left = right = 0.0
    for k in range(1, 101):
        left += 7.5 * 0.01
        right += 12.5 * 0.01
        o.update(left, right, k * 0.01)
    assert (o.x, o.y, o.heading) == pytest.approx((math.sin(1), 1 - math.cos(1), 1.0), abs=1e-6)
    mean = RollingMean(10)
    for v in range(1, 13):
        mean.accumulate(float(v))
    assert mean.mean() == 7.5


def test_speed_limiter_reaches_one_metre_per_second_at_update_500() -> None:
    cm, ctrl, wheels = diff_drive_system(
        {
            "linear.x.has_acceleration_limits": True,
            "linear.x.max_acceleration": 2.0,
            "linear.x.min_acceleration": -4.0,
            "wheel_radius": 0.1,
            "wheel_separation": 1.0,
            "open_loop": True,
        }
    )
    commands = []
    for _ in range(500):
        ctrl.set_command(1.0, 0.0, cm.time_s + 0.001)
        cm.step(0.001)
        commands.append(wheels[0].get())
    assert all(c < 10.0 for c in commands[:499])
    assert commands[499] == pytest.approx(10.0, abs=1e-3)
    for k in range(250):  # deceleration -4 m/s² -> 0 after 250 updates
        ctrl.set_command(0.0, 0.0, cm.time_s + 0.001)
        cm.step(0.001)
        if k < 249:
            assert wheels[0].get() > 0.0
    assert wheels[0].get() == pytest.approx(0.0, abs=1e-3)


def test_jtc_segments() -> None:
    t = Trajectory(0.0, [P(1, (0,), (-2,)), P(3, (4,), (10,))], 0.0, P(0, (0,)))
    s = t.sample(1 + math.sqrt(2))
    assert s is not None
    assert (s.positions[0], s.velocities[0], s.accelerations[0]) == pytest.approx(
        (0.0, 4.0, 8.485281), abs=1e-6
    )
    s = t.sample(3 - 1e-12)
    assert s is not None and s.accelerations[0] == pytest.approx(12.0, abs=1e-6)
    t = Trajectory(0.0, [P(1, (0,), (24,), (-100,)), P(3, (0,), (4,), (0,))], 0.0, P(0, (0,)))
    s = t.sample(2.0)
    assert s is not None
    assert (s.positions[0], s.velocities[0], s.accelerations[0]) == pytest.approx((0, -6, 10))
    t = Trajectory(0.0, [P(1, (1,)), P(2, (2,)), P(3, (3,))], 0.0, P(0, (0,)))
    s = t.sample(0.5)
    assert s is not None and (s.positions[0], s.velocities[0], s.accelerations[0]) == (0.5, 1, 0)
    s = t.sample(3.125)
    assert s is not None and s.positions[0] == 3 and s.velocities[0] == 0.0
    assert t.sample(-0.1) is None


def test_pid_classic_and_kilted() -> None:
    pid = Pid(Gains.from_params({"p": 100.0, "i": 0.01, "d": 10.0}))
    out = [pid.compute(e, 0.01) for e in (1.0, 0.9, 0.8)]
    assert out == pytest.approx([1100.0, -10.0, -20.0], abs=1e-9)
    pid = Pid(Gains.from_params({"p": 100.0, "i": 0.01, "d": 10.0, "i_clamp": 1.0}))
    out = [pid.compute(e, 0.01) for e in (1.0, 0.9, 0.8)]
    assert out == pytest.approx([1100.0001, -9.99981, -19.99973], abs=1e-9)
    assert pid.compute(1.0, 0.0) == 0.0 and pid.compute(math.nan, 0.01) == 0.0
    k = PidKilted(
        1.0, 10.0, u_clamp_min=-2, u_clamp_max=2, antiwindup=AntiWindup.CONDITIONAL_INTEGRATION
    )
    assert [k.compute(1.0, 0.1) for _ in range(5)] == [1, 2, 2, 2, 2]


def test_transmissions_both_directions() -> None:
    s = SimpleTransmission(10.0, 1.0)
    assert s.actuator_to_joint_effort([1.0]) == [10.0]
    assert s.actuator_to_joint_velocity([1.0]) == [0.1]
    assert s.actuator_to_joint_position([1.0]) == [1.1]
    for f, g in (
        (s.actuator_to_joint_effort, s.joint_to_actuator_effort),
        (s.actuator_to_joint_velocity, s.joint_to_actuator_velocity),
        (s.actuator_to_joint_position, s.joint_to_actuator_position),
    ):
        assert g(f([0.7]))[0] == pytest.approx(0.7)
    d = DifferentialTransmission([10, 10], [2, 2])
    assert d.actuator_to_joint_effort([10, 10]) == [400, 0]
    assert d.actuator_to_joint_velocity([10, 10]) == [0.5, 0]
    assert d.actuator_to_joint_position([10, 10]) == [0.5, 0]
    assert d.actuator_to_joint_effort([10, -10]) == [0, 400]
    assert d.actuator_to_joint_velocity([10, -10]) == [0, 0.5]
    d = DifferentialTransmission([10, 5], [2, 3], [0.1, -0.2])
    for f, g in (
        (d.actuator_to_joint_effort, d.joint_to_actuator_effort),
        (d.actuator_to_joint_velocity, d.joint_to_actuator_velocity),
        (d.actuator_to_joint_position, d.joint_to_actuator_position),
    ):
        assert g(f([0.3, -1.2])) == pytest.approx([0.3, -1.2])


def test_transmissions_from_urdf_both_directions() -> None:
    from robomodel.control.transmissions import TransmissionError, TransmissionSet
    from robomodel.loading import load

    urdf = """<robot name="t"><link name="a"/><link name="b"/><link name="c"/>
    <joint name="j" type="continuous"><parent link="a"/><child link="b"/></joint>
    <joint name="k" type="continuous"><parent link="b"/><child link="c"/></joint>
    <transmission name="t1"><type>transmission_interface/SimpleTransmission</type>
      <joint name="j"><offset>1.0</offset>
        <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
      <actuator name="m"><mechanicalReduction>10</mechanicalReduction></actuator></transmission>
    <ros2_control name="S" type="system"><hardware><plugin>mock_components/GenericSystem</plugin></hardware>
      <joint name="k"><command_interface name="effort"/><state_interface name="position"/></joint>
      <transmission name="t2"><plugin>transmission_interface/DifferentialTransmission</plugin>
        <actuator name="m2" role="actuator2"><mechanical_reduction>10</mechanical_reduction></actuator>
        <actuator name="m1" role="actuator1"><mechanical_reduction>10</mechanical_reduction></actuator>
        <joint name="k" role="joint1"><mechanical_reduction>2</mechanical_reduction></joint>
        <joint name="j" role="joint2"><mechanical_reduction>2</mechanical_reduction></joint>
      </transmission></ros2_control></robot>"""
    robot = load(urdf)
    ts = TransmissionSet.from_robot(robot)  # type: ignore[arg-type]
    assert ts.actuator_names == ("m", "m1", "m2") and ts.joint_names == ("j", "k", "j")
    assert ts.actuator_to_joint("position", {"m": 1.0}) == {"j": 1.1}
    assert ts.joint_to_actuator("effort", {"j": 10.0}) == {"m": 1.0}
    assert ts.actuator_to_joint("effort", {"m1": 10.0, "m2": -10.0}) == {"k": 0.0, "j": 400.0}
    back = ts.joint_to_actuator(
        "velocity", ts.actuator_to_joint("velocity", {"m1": 3.0, "m2": 1.0})
    )
    assert (back["m1"], back["m2"]) == pytest.approx((3.0, 1.0))
    with pytest.raises(TransmissionError, match="must not be 0"):
        SimpleTransmission(0.0)
