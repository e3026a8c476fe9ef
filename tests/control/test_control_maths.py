"""The control maths against what must hold of them: a trajectory segment meets the boundary
values it is given and its velocity and acceleration are the derivatives of its position; the
PIDs' terms, clamps and anti-windup as control_toolbox's pid.cpp computes them, step by step;
odometry against the pose of a drive whose path is known."""

from __future__ import annotations

import math
from typing import Any

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from robomodel.control import ControllerManager, ControlSystem, load_controller_config
from robomodel.control.controllers import Odometry, RollingMean, Trajectory, TrajectoryPoint
from robomodel.control.controllers.trajectory import interpolate
from robomodel.control.exceptions import ConfigError
from robomodel.control.hardware import ResourceManager, hardware_from_robot
from robomodel.control.pid import AntiWindup, Gains, Pid, PidKilted
from robomodel.loading import load
from robomodel.runtime import Context
from robomodel.runtime.clock import ManualClock
from robomodel.runtime.msg import Odometry as OdometryMsg
from robomodel.runtime.msg import TFMessage, Time, Twist, TwistStamped, Vector3
from tests.control.helpers import WHEEL, WHEELS

P = TrajectoryPoint
value = st.floats(-10.0, 10.0)


@settings(max_examples=60, deadline=None)
@given(
    p=st.tuples(value, value),
    v=st.tuples(value, value),
    a=st.tuples(value, value),
    duration_s=st.floats(0.5, 4.0),
    degree=st.sampled_from([1, 3, 5]),
)
def test_a_segment_meets_its_ends_and_its_rates_are_derivatives(
    p: tuple[float, float],
    v: tuple[float, float],
    a: tuple[float, float],
    duration_s: float,
    degree: int,
) -> None:
    """Linear meets the positions, cubic the velocities too, quintic the accelerations too."""
    vel = (lambda x: (x,)) if degree >= 3 else (lambda x: ())
    acc = (lambda x: (x,)) if degree == 5 else (lambda x: ())
    start = P(0.0, (p[0],), vel(v[0]), acc(a[0]))
    end = P(0.0, (p[1],), vel(v[1]), acc(a[1]))
    t0 = 2.0
    t1 = t0 + duration_s

    def at(t: float) -> tuple[float, float, float]:
        pos, vels, accs = interpolate(t0, start, t1, end, t)
        return pos[0], vels[0], accs[0]

    assert at(t0)[0] == pytest.approx(p[0], abs=1e-9)
    assert at(t1)[0] == pytest.approx(p[1], abs=1e-9)
    if degree >= 3:
        assert (at(t0)[1], at(t1)[1]) == pytest.approx(v, abs=1e-8)
    if degree == 5:
        assert (at(t0)[2], at(t1)[2]) == pytest.approx(a, abs=1e-7)
    h = 1e-5
    for t in (t0 + 0.3 * duration_s, t0 + 0.7 * duration_s):
        before, here, after = at(t - h), at(t), at(t + h)
        assert here[1] == pytest.approx((after[0] - before[0]) / (2 * h), rel=1e-5, abs=1e-5)
        assert here[2] == pytest.approx((after[1] - before[1]) / (2 * h), rel=1e-5, abs=1e-5)
    if degree == 1:
        assert at(t0 + 0.5 * duration_s)[2] == 0.0
    # outside the segment the ends are held
    assert at(t0 - 1.0)[0] == pytest.approx(p[0], abs=1e-9)
    assert at(t1 + 1.0)[0] == pytest.approx(p[1], abs=1e-9)


def test_a_segment_is_linear_unless_both_ends_have_velocities() -> None:
    """interpolate_between_points: a cubic needs velocities at both ends, else a line."""
    a, b = P(0.0, (0.0,), (4.0,)), P(1.0, (2.0,))
    for first, second in ((a, b), (b, a)):
        p, v, acc = interpolate(0.0, first, 1.0, second, 0.25)
        start, end = first.positions[0], second.positions[0]
        assert (p, v, acc) == ((start + 0.25 * (end - start),), (end - start,), (0.0,))


def test_a_segment_of_no_duration_is_its_end_at_rest() -> None:
    start, end = P(0.0, (1.0,), (2.0,), (3.0,)), P(0.0, (5.0,), (6.0,), (7.0,))
    for t0 in (1.0, 2.0):  # zero and negative durations
        assert interpolate(t0, start, 1.0, end, 1.0) == ((5.0,), (0.0,), (0.0,))
    assert interpolate(1.0, P(0.0, (1.0,)), 1.0, P(0.0, (5.0,)), 1.0) == ((5.0,), (0.0,), (0.0,))


def test_the_state_before_starts_the_first_segment_with_what_the_waypoint_has() -> None:
    # the first waypoint has velocities: a state without them starts at rest (cubic)
    t = Trajectory(10.0, [P(2.0, (4.0, -4.0), (0.0, 0.0))], 9.0, P(0.0, (0.0, 0.0)))
    first = t.sample(9.0)
    assert first is not None and first.segment == 0
    assert first.positions == (0.0, 0.0) and first.velocities == (0.0, 0.0)
    middle = t.sample(10.5)  # halfway through 3 s: a cubic from rest to rest
    assert middle is not None and middle.segment == 0
    assert middle.positions == pytest.approx((2.0, -2.0))
    assert middle.velocities == pytest.approx((2.0, -2.0))  # 1.5 * 4 / 3
    assert middle.accelerations == pytest.approx((0.0, 0.0), abs=1e-12)
    # a state with velocities but a waypoint without: linear, the velocities are not used
    t = Trajectory(0.0, [P(2.0, (4.0,))], 0.0, P(0.0, (0.0,), (100.0,), (100.0,)))
    s = t.sample(1.0)
    assert s is not None and s.velocities == (2.0,)
    assert (s.positions, s.accelerations) == ((2.0,), (0.0,))
    # accelerations without velocities in the waypoint: not quintic
    t = Trajectory(0.0, [P(2.0, (4.0,), (), (1.0,))], 0.0, P(0.0, (0.0,), (), (5.0,)))
    s = t.sample(1.0)
    assert s is not None and (s.positions, s.accelerations) == ((2.0,), (0.0,))
    # a state with accelerations into a quintic waypoint
    t = Trajectory(0.0, [P(2.0, (4.0,), (0.0,), (0.0,))], 0.0, P(0.0, (0.0,), (), (3.0,)))
    s = t.sample(0.0)
    assert s is not None and s.accelerations == pytest.approx((3.0,))
    t = Trajectory(0.0, [P(2.0, (4.0,), (0.0,), (0.0,))], 0.0, P(0.0, (0.0,)))
    s = t.sample(0.0)
    assert s is not None and (s.velocities, s.accelerations) == ((0.0,), (0.0,))


def test_sampling_walks_the_waypoints_and_holds_the_last() -> None:
    points = [P(1.0, (1.0,), (0.0,)), P(2.0, (3.0,), (2.0,)), P(4.0, (3.0,), (0.0,))]
    t = Trajectory(100.0, points, 99.0, P(0.0, (0.0,), (0.0,)))
    assert t.end_s == 104.0
    assert t.sample(98.9) is None
    segments = [(time_s, t.sample(time_s)) for time_s in (99.5, 100.5, 101.0, 101.5, 103.0)]
    assert [s.segment for _, s in segments if s is not None] == [0, 0, 1, 1, 2]
    at_waypoint = t.sample(101.0)
    assert at_waypoint is not None and at_waypoint.positions == pytest.approx((1.0,))
    mid_first = t.sample(101.5)  # cubic (1, 0) -> (3, 2) over 1 s, halfway
    assert mid_first is not None and mid_first.positions == pytest.approx((1.75,))
    mid_second = t.sample(103.0)  # cubic (3, 2) -> (3, 0) over 2 s, halfway
    assert mid_second is not None and mid_second.positions == pytest.approx((3.5,))
    at_second = t.sample(102.0)
    assert at_second is not None and at_second.positions == pytest.approx((3.0,))
    assert at_second.velocities == pytest.approx((2.0,)) and at_second.segment == 2
    after = t.sample(104.0)
    assert after is not None and after.segment == 3 and after.positions == (3.0,)
    assert after.velocities == (0.0,) and after.accelerations == (0.0,)
    moving_end = Trajectory(0.0, [P(1.0, (2.0,), (0.5,), (0.25,))], 0.0, P(0.0, (0.0,)))
    held = moving_end.sample(5.0)
    assert held is not None and held.segment == 1
    assert (held.positions, held.velocities, held.accelerations) == ((2.0,), (0.5,), (0.25,))


def test_gains_from_parameters_as_pid_init_reads_them() -> None:
    assert Gains.from_params({"p": 1, "i": 2, "d": 3, "i_clamp": -4}) == Gains(
        1.0, 2.0, 3.0, i_max=4.0, i_min=-4.0
    )
    assert Gains.from_params({"g.p": 1, "g.i_clamp": 4, "g.i_clamp_min": -1}, "g.") == Gains(
        1.0, i_max=4.0, i_min=-1.0
    )
    assert Gains.from_params({"p": 1, "i_clamp_max": 2, "antiwindup": True}) == Gains(
        1.0, i_max=2.0, i_min=0.0, antiwindup=True
    )
    assert Gains.from_params({"p": 5}) == Gains(5.0)
    with pytest.raises(ConfigError, match=r"^PID gain 'g\.p' is required \(control_toolbox"):
        Gains.from_params({"g.i": 1.0}, "g.")
    with pytest.raises(ConfigError, match=r"^PID gain 'g\.d' must be a number, got 'x'$"):
        Gains.from_params({"g.p": 1.0, "g.d": "x"}, "g.")
    with pytest.raises(ConfigError, match=r"^PID gain 'i' must be a number, got None$"):
        Gains.from_params({"p": 1.0, "i": None})


def test_classic_pid_terms_step_by_step() -> None:
    """p·e + clamp(i·∫e, i_min, i_max) + d·ė, with ė by finite difference of the error."""
    pid = Pid(Gains(p=2.0, i=10.0, d=0.5, i_max=3.0, i_min=-1.0))
    assert pid.compute(1.0, 0.1) == pytest.approx(2.0 + 1.0 + 0.5 * 10.0)
    assert (pid.p_error, pid.i_error, pid.d_error) == pytest.approx((1.0, 0.1, 10.0))
    assert pid.compute(3.0, 0.1) == pytest.approx(6.0 + 3.0 + 0.5 * 20.0)  # i clamped at 3
    assert pid.i_error == pytest.approx(0.4)  # the state is not clamped without antiwindup
    assert pid.compute(-9.0, 0.1) == pytest.approx(-18.0 + -1.0 + 0.5 * -120.0)
    assert pid.error_last == -9.0
    pid.reset()
    assert (pid.p_error, pid.i_error, pid.d_error, pid.error_last) == (0.0, 0.0, 0.0, 0.0)
    # a zero or non-finite step, or a non-finite error, commands nothing and keeps the state
    assert pid.compute(1.0, 0.0) == 0.0 and pid.compute(math.inf, 0.1) == 0.0
    assert pid.error_last == 0.0
    assert pid.compute(1.0, 1e-320) == 0.0  # the error rate overflows
    assert pid.compute_with_rate(1.0, math.nan, 0.1) == 0.0
    assert pid.compute_with_rate(math.inf, 0.0, 0.1) == 0.0
    assert pid.compute_with_rate(1.0, 0.0, 0.0) == 0.0
    assert pid.i_error == 0.0
    assert pid.compute_with_rate(2.0, -4.0, 0.1) == pytest.approx(4.0 + 2.0 - 2.0)
    assert (pid.p_error, pid.i_error, pid.d_error) == pytest.approx((2.0, 0.2, -4.0))


@settings(max_examples=40, deadline=None)
@given(
    errors=st.lists(st.floats(-5.0, 5.0), min_size=1, max_size=8),
    gains=st.tuples(
        st.floats(-3.0, 3.0), st.floats(-3.0, 3.0), st.floats(-1.0, 1.0), st.floats(0.0, 2.0)
    ),
    antiwindup=st.booleans(),
)
def test_compute_is_compute_with_rate_of_the_error_s_difference(
    errors: list[float], gains: tuple[float, float, float, float], antiwindup: bool
) -> None:
    p, i, d, clamp = gains
    g = Gains(p, i, d, i_max=clamp, i_min=-clamp / 2, antiwindup=antiwindup)
    by_difference, by_rate = Pid(g), Pid(g)
    last, dt_s = 0.0, 0.01
    for error in errors:
        got = by_difference.compute(error, dt_s)
        want = by_rate.compute_with_rate(error, (error - last) / dt_s, dt_s)
        assert got == pytest.approx(want, rel=1e-12, abs=1e-9)
        assert by_difference.i_error == pytest.approx(by_rate.i_error, abs=1e-12)
        last = error


@pytest.mark.parametrize("i", [2.0, -2.0, 1.0])
def test_classic_antiwindup_bounds_the_integral_state(i: float) -> None:
    """With antiwindup the integral itself is kept within [i_min, i_max] / i (the bounds
    swap for a negative gain), so the command leaves the limit as soon as the error turns."""
    for compute in ("compute", "compute_with_rate"):
        pid = Pid(Gains(p=0.0, i=i, i_max=1.0, i_min=-0.5, antiwindup=True))
        step = getattr(pid, compute)
        args = (lambda e: (e, 0.1)) if compute == "compute" else (lambda e: (e, 0.0, 0.1))
        for _ in range(10):
            out = step(*args(5.0 if i > 0 else -5.0))
        assert out == pytest.approx(1.0)
        assert pid.i_error == pytest.approx(1.0 / i)
        out = step(*args(-1.0 if i > 0 else 1.0))
        assert out == pytest.approx(i * (1.0 / i + (-0.1 if i > 0 else 0.1)))


def test_classic_antiwindup_holds_the_integral_at_its_lower_bound() -> None:
    """The lower bound of the integral state is i_min / i, as the upper one is i_max / i."""
    pid = Pid(Gains(p=0.0, i=2.0, i_max=1.0, i_min=-0.5, antiwindup=True))
    for _ in range(10):
        out = pid.compute_with_rate(-5.0, 0.0, 0.1)
    assert out == pytest.approx(-0.5)
    assert pid.i_error == pytest.approx(-0.25)


def test_new_gains_keep_the_integral_and_their_bounds_apply() -> None:
    pid = Pid(Gains(p=0.0, i=1.0, i_max=10.0, i_min=-10.0, antiwindup=True))
    for _ in range(5):
        pid.compute_with_rate(2.0, 0.0, 0.1)
    assert pid.i_error == pytest.approx(1.0)
    assert pid.set_gains(Gains(p=0.0, i=4.0, i_max=2.0, i_min=-2.0, antiwindup=True))
    assert pid.compute_with_rate(1.0, 0.0, 0.1) == pytest.approx(2.0)  # 4 * min(1.1, 0.5)
    assert pid.i_error == pytest.approx(0.5)


def test_kilted_tracking_time_constant_defaults() -> None:
    assert PidKilted(2.0, 8.0, 0.18).tracking_time_constant == pytest.approx(0.15)  # √(d/i)
    assert PidKilted(2.0, 8.0).tracking_time_constant == pytest.approx(0.25)  # p/i
    assert PidKilted(2.0).tracking_time_constant == 0.0
    assert PidKilted(2.0, 8.0, tracking_time_constant=3.0).tracking_time_constant == 3.0


def test_kilted_pid_step_by_step() -> None:
    k = PidKilted(1.0, 10.0, 0.1, i_clamp_min=-0.3, i_clamp_max=0.25)
    assert k.compute(1.0, 0.1) == pytest.approx(1.0 + 0.0 + 0.1 * 10.0)  # the integral lags
    assert k.i_term == pytest.approx(0.25)  # 1.0 clamped to 0.25
    assert k.compute(2.0, 0.1) == pytest.approx(2.0 + 0.25 + 0.1 * 10.0)
    assert k.compute(2.0, 0.0) == pytest.approx(3.25)  # dt 0: the last command again
    assert math.isnan(k.compute(math.nan, 0.1))
    with pytest.raises(ValueError, match=r"^PID: dt must be non-negative$"):
        k.compute(1.0, -0.1)
    k.reset()
    assert (k.i_term, k.error_last, k.cmd) == (0.0, 0.0, 0.0)
    assert k.compute(-4.0, 0.1) == pytest.approx(-4.0 - 4.0)
    assert k.i_term == pytest.approx(-0.3)


def test_kilted_deadband_stops_the_integral() -> None:
    k = PidKilted(0.0, 1.0, error_deadband=0.5)
    for error in (0.5, 0.4, -0.5):
        k.compute(error, 1.0)
    assert k.i_term == 0.0
    k.compute(0.6, 1.0)
    k.compute(0.6, 1.0)
    assert k.i_term == pytest.approx(1.2)  # integrates without a clamp
    at_edge = PidKilted(0.0, 1.0, error_deadband=0.25)
    at_edge.compute(0.25, 1.0)  # |error| <= deadband is in it (control_toolbox's is_zero)
    assert at_edge.i_term == 0.0


def test_kilted_back_calculation_unwinds_by_the_saturation() -> None:
    k = PidKilted(
        1.0, 2.0, u_clamp_min=-1.0, u_clamp_max=1.5, antiwindup=AntiWindup.BACK_CALCULATION,
        tracking_time_constant=0.5,
    )  # fmt: skip
    assert k.compute(3.0, 0.1) == 1.5  # unsaturated 3
    assert k.i_term == pytest.approx(0.1 * (2.0 * 3.0 + (1.5 - 3.0) / 0.5))
    assert k.compute(-3.0, 0.1) == -1.0  # unsaturated -3 + 0.3
    assert k.i_term == pytest.approx(0.3 + 0.1 * (2.0 * -3.0 + (-1.0 + 2.7) / 0.5))
    # with no integral gain, back calculation integrates nothing
    k = PidKilted(1.0, 0.0, u_clamp_max=1.0, antiwindup=AntiWindup.BACK_CALCULATION)
    k.compute(3.0, 0.1)
    assert k.i_term == 0.0


def test_kilted_conditional_integration_only_when_it_does_not_wind_up() -> None:
    k = PidKilted(
        1.0, 1.0, u_clamp_min=-2.0, u_clamp_max=2.0,
        antiwindup=AntiWindup.CONDITIONAL_INTEGRATION,
    )  # fmt: skip
    k.compute(1.5, 0.5)  # not saturated: integrates
    assert k.i_term == pytest.approx(0.75)
    k.compute(3.0, 0.5)  # saturated, pushing further out: holds
    assert k.i_term == pytest.approx(0.75)
    k.compute(-1.5, 0.5)  # unsaturated -0.75: integrates
    assert k.i_term == pytest.approx(0.0)
    k.compute(-3.0, 0.5)  # saturated below, error below: holds
    assert k.i_term == pytest.approx(0.0)
    k = PidKilted(
        1.0, 1.0, u_clamp_min=0.5, u_clamp_max=2.0,
        antiwindup=AntiWindup.CONDITIONAL_INTEGRATION,
    )  # fmt: skip
    k.i_term = -2.0  # an unsaturated command of 0, saturated to 0.5: integrates
    assert k.compute(2.0, 0.5) == 0.5
    assert k.i_term == pytest.approx(-1.0)
    k = PidKilted(
        0.0, 1.0, u_clamp_max=1.0, antiwindup=AntiWindup.CONDITIONAL_INTEGRATION
    )  # fmt: skip
    k.i_term = 5.0  # saturated by the integral, the error pulling back: integrates
    k.compute(-1.0, 0.5)
    assert k.i_term == pytest.approx(4.5)
    k = PidKilted(1.0, 1.0, u_clamp_max=0.1, antiwindup=AntiWindup.CONDITIONAL_INTEGRATION)
    k.compute(0.5, 0.5)  # saturated (0.5 to 0.1), error and command of one sign: holds
    assert k.i_term == 0.0


def test_rolling_mean_over_the_last_window_values() -> None:
    mean = RollingMean(3)
    assert mean.mean() == 0.0 and mean.filled == 0
    mean.accumulate(3.0)
    assert mean.mean() == 3.0 and mean.filled == 1
    for v in (6.0, 9.0, 12.0, 0.0):
        mean.accumulate(v)
    assert mean.mean() == pytest.approx(7.0) and mean.filled == 3
    assert RollingMean(0).window == 1 and RollingMean(-5).window == 1
    one = RollingMean(0)
    one.accumulate(2.0)
    one.accumulate(5.0)
    assert one.mean() == 5.0


def test_odometry_follows_a_straight_line_then_an_arc() -> None:
    o = Odometry(2)
    o.set_wheel_params(0.4, 0.1, 0.2)  # wheel radii differ
    o.init(1.0)
    assert o.update(10.0, 5.0, 2.0)  # both wheels 1 m
    assert (o.x, o.y, o.heading) == pytest.approx((1.0, 0.0, 0.0))
    assert (o.linear, o.angular) == pytest.approx((1.0, 0.0))
    assert o.timestamp_s == 2.0
    assert not o.update(100.0, 100.0, 2.00005)  # too soon: nothing changes
    assert (o.x, o.heading, o.timestamp_s) == (pytest.approx(1.0), 0.0, 2.0)
    # a quarter circle of radius 1 to the left in 0.5 s: left 0.8·π/2, right 1.2·π/2
    quarter = math.pi / 2
    assert o.update(10.0 + 8.0 * quarter, 5.0 + 6.0 * quarter, 2.5)
    assert (o.x, o.y, o.heading) == pytest.approx((2.0, 1.0, quarter))
    assert o.linear == pytest.approx((1.0 + quarter / 0.5) / 2)  # the mean of the two updates
    assert o.angular == pytest.approx(quarter / 0.5 / 2)
    o.update_open_loop(1.0, 0.0, 3.5)  # one more metre along the heading, the rate as given
    assert (o.x, o.y, o.linear, o.angular) == pytest.approx((2.0, 2.0, 1.0, 0.0))
    o.init(4.0)  # keeps the pose, forgets the velocity means
    o.update_from_velocity(1.0, 1.0, 5.0)
    assert (o.x, o.y, o.linear) == pytest.approx((2.0, 3.0, 1.0))
    o.reset_odometry()
    assert (o.x, o.y, o.heading, o.linear, o.angular) == (0.0, 0.0, 0.0, 0.0, 0.0)
    assert o.update(0.0, 0.0, 6.0) and o.x == 0.0  # the wheel positions were forgotten too


def test_odometry_at_the_time_of_the_last_update_moves_but_gives_no_velocity() -> None:
    o = Odometry(2)
    o.set_wheel_params(0.5, 0.1, 0.1)
    o.init(0.0)
    assert o.update_from_velocity(0.2, 0.2, 0.0)  # the first update after init, dt 0
    assert (o.x, o.linear, o.angular) == (pytest.approx(0.2), 0.0, 0.0)
    assert o.update(1.0, 1.0, 0.0001)  # 1e-4 s is enough (odometry.cpp: dt < 0.0001 is not)
    assert o.timestamp_s == 0.0001


def test_odometry_runge_kutta_heads_along_the_mean_heading() -> None:
    o = Odometry()
    o.integrate_runge_kutta2(2.0, 1.0)
    assert (o.x, o.y, o.heading) == pytest.approx((2 * math.cos(0.5), 2 * math.sin(0.5), 1.0))


def test_odometry_runge_kutta_on_a_nearly_straight_step() -> None:
    o = Odometry()
    o.set_wheel_params(1.0, 1.0, 1.0)
    o.heading = 0.5
    o.integrate_exact(2.0, 4e-7)
    assert (o.x, o.y) == pytest.approx((2 * math.cos(0.5 + 2e-7), 2 * math.sin(0.5 + 2e-7)))
    assert o.heading == pytest.approx(0.5 + 4e-7, abs=1e-15)
    o = Odometry()
    o.integrate_exact(1.0, -math.pi)  # a half turn to the right, radius 1/π
    assert (o.x, o.y, o.heading) == pytest.approx((0.0, -2 / math.pi, -math.pi), abs=1e-12)


def _driven(extra: str, steps: int, command: Any) -> tuple[list[Any], list[Any], Any]:
    """A diff drive at 100 Hz over the in-process transport, ``command(publisher, time_s)``
    called before each update; the odometry and tf messages it published, and itself."""
    ctx = Context("inproc", clock=ManualClock())
    robot = load(
        WHEELS.format(joints=WHEEL.format(name="left_wheel") + WHEEL.format(name="right_wheel"))
    )
    cfg = load_controller_config(
        "dd.yaml",
        text="controller_manager:\n  ros__parameters:\n    update_rate: 100\n"
        "    dd:\n      type: diff_drive_controller/DiffDriveController\n"
        "dd:\n  ros__parameters:\n    left_wheel_names: [left_wheel]\n"
        "    right_wheel_names: [right_wheel]\n    wheel_separation: 0.5\n"
        "    wheel_radius: 0.1\n    publish_rate: 100.0\n" + extra,
    )
    system = ControlSystem.build(robot, cfg, context=ctx)
    node = ctx.create_node("probe")
    odoms: list[OdometryMsg] = []
    tfs: list[TFMessage] = []
    node.create_subscription(OdometryMsg, "/dd/odom", odoms.append)
    node.create_subscription(TFMessage, "/tf", tfs.append)
    stamped = "use_stamped_vel: false" not in extra
    pub = node.create_publisher(
        TwistStamped if stamped else Twist, "/dd/cmd_vel" if stamped else "/dd/cmd_vel_unstamped"
    )
    controller = system.manager.entries["dd"].controller
    for _ in range(steps):
        command(pub, system.manager.time_s)
        ctx.spin_once()
        ctx.advance(0.01)
        system.manager.step(0.01)
    ctx.spin_once()
    ctx.shutdown()
    return odoms, tfs, controller


def test_diff_drive_odometry_carries_the_heading_and_the_update_time() -> None:
    def turn(pub: Any, time_s: float) -> None:
        msg = TwistStamped()
        msg.header.stamp = Time(int(time_s), round((time_s % 1) * 1e9))
        msg.twist.linear.x, msg.twist.angular.z = 0.1, 1.5
        pub.publish(msg)

    odoms, tfs, controller = _driven("", 130, turn)
    last, tf = odoms[-1], tfs[-1].transforms[0]
    heading = controller.odometry.heading
    assert heading > 1.0  # turned left about 1.5 rad/s for 1.3 s
    q = last.pose.pose.orientation
    assert (q.x, q.y) == (0.0, 0.0) and q.z**2 + q.w**2 == pytest.approx(1.0)
    assert math.atan2(2 * q.w * q.z, 1 - 2 * q.z * q.z) == pytest.approx(heading)
    assert tf.transform.rotation == q
    assert (tf.transform.translation.x, tf.transform.translation.y) == (
        last.pose.pose.position.x, last.pose.pose.position.y
    )  # fmt: skip
    assert last.twist.twist.angular.z == pytest.approx(1.5, abs=0.05)
    stamps = [(o.header.stamp.sec, o.header.stamp.nanosec) for o in odoms[-3:]]
    assert stamps == [(1, 280_000_000), (1, 290_000_000), (1, 300_000_000)]
    assert (tf.header.stamp.sec, tf.header.stamp.nanosec) == (1, 300_000_000)


def test_diff_drive_takes_the_command_s_stamp_and_the_unstamped_twist() -> None:
    def stale(pub: Any, time_s: float) -> None:
        msg = TwistStamped()
        msg.header.stamp = Time(0, 1)  # older than cmd_vel_timeout (0.5 s) after 0.5 s
        msg.twist.linear.x = 0.3
        pub.publish(msg)

    odoms, _, _ = _driven("", 100, stale)
    assert odoms[-1].twist.twist.linear.x == pytest.approx(0.0, abs=1e-9)
    assert odoms[10].twist.twist.linear.x > 0.1  # taken while it was fresh

    def unstamped(pub: Any, time_s: float) -> None:
        pub.publish(Twist(Vector3(0.2, 0.0, 0.0), Vector3(0.0, 0.0, -0.5)))

    odoms, _, controller = _driven("    use_stamped_vel: false\n", 60, unstamped)
    assert odoms[-1].twist.twist.linear.x == pytest.approx(0.2, abs=1e-3)
    assert odoms[-1].twist.twist.angular.z == pytest.approx(-0.5, abs=1e-3)
    assert controller.odometry.heading < -0.2


DERIVED = """<robot name="base"><link name="base_link"/>
<link name="l"><collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>
<collision><geometry><cylinder radius="0.08" length="0.02"/></geometry></collision>
<collision><geometry><sphere radius="0.5"/></geometry></collision></link>
<link name="r"><collision><geometry><cylinder radius="0.3" length="0.02"/></geometry></collision></link>
<joint name="left_wheel" type="continuous"><parent link="base_link"/><child link="l"/>
<origin xyz="0.1 0.3 0.05"/></joint>
<joint name="right_wheel" type="continuous"><parent link="base_link"/><child link="r"/>
<origin xyz="-0.1 -0.2 0.07"/></joint>
<ros2_control name="Base" type="system"><hardware><plugin>mock_components/GenericSystem</plugin>
</hardware>{joints}</ros2_control></robot>"""


@pytest.mark.parametrize(
    ("given", "separation_m", "radius_m"),
    [
        ({}, math.hypot(0.2, 0.5), 0.08),  # the first collision with a radius, of the left wheel
        ({"wheel_separation": 0.7}, 0.7, 0.08),
        ({"wheel_radius": 0.5}, math.hypot(0.2, 0.5), 0.5),
    ],
)
def test_diff_drive_derives_wheel_parameters_from_the_urdf(
    given: dict[str, float], separation_m: float, radius_m: float
) -> None:
    """As RCS1's getWheelParams: the x-y distance of the wheel joints and the left wheel's
    collision radius, each only where the parameters do not give it."""
    robot = load(
        DERIVED.format(joints=WHEEL.format(name="left_wheel") + WHEEL.format(name="right_wheel"))
    )
    manager = ControllerManager(ResourceManager(hardware_from_robot(robot)), robot=robot)
    manager.load_controller(
        "dd",
        "diff_drive_controller/DiffDriveController",
        {
            "left_wheel_names": ["left_wheel"],
            "right_wheel_names": ["right_wheel"],
            "derive_wheel_params_from_urdf": True,
            **given,
        },
    )
    controller = manager.entries["dd"].controller
    assert controller.wheel_separation == pytest.approx(separation_m)
    assert controller.wheel_radius == pytest.approx(radius_m)
