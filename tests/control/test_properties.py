"""Property tests: transmissions invert each other; PID and limiter invariants."""

from __future__ import annotations

import math

import pytest
from hypothesis import given
from hypothesis import strategies as st

from robomodel.control import Gains, Pid
from robomodel.control.controllers import SpeedLimiter
from robomodel.control.transmissions import DifferentialTransmission, SimpleTransmission

finite = st.floats(-1e3, 1e3, allow_nan=False)
reduction = st.one_of(st.floats(0.01, 100.0), st.floats(-100.0, -0.01))


@given(reduction, finite, finite)
def test_simple_transmission_round_trips(n: float, offset: float, x: float) -> None:
    t = SimpleTransmission(n, offset)
    for kind in ("effort", "velocity", "position"):
        to_joint = getattr(t, f"actuator_to_joint_{kind}")
        to_act = getattr(t, f"joint_to_actuator_{kind}")
        assert to_act(to_joint([x]))[0] == pytest.approx(x, rel=1e-9, abs=1e-6)
    # power is conserved: effort × velocity is the same on both sides
    assert t.actuator_to_joint_effort([x])[0] * t.actuator_to_joint_velocity([1.0])[
        0
    ] == pytest.approx(x)


@given(reduction, reduction, reduction, reduction, finite, finite, finite, finite)
def test_differential_transmission_round_trips(
    a0: float, a1: float, j0: float, j1: float, o0: float, o1: float, x0: float, x1: float
) -> None:
    t = DifferentialTransmission([a0, a1], [j0, j1], [o0, o1])
    for kind in ("effort", "velocity", "position"):
        to_joint = getattr(t, f"actuator_to_joint_{kind}")
        to_act = getattr(t, f"joint_to_actuator_{kind}")
        assert to_act(to_joint([x0, x1])) == pytest.approx([x0, x1], rel=1e-7, abs=1e-6)
    effort = t.actuator_to_joint_effort([x0, x1])
    velocity = t.actuator_to_joint_velocity([x1, -x0])
    assert effort[0] * velocity[0] + effort[1] * velocity[1] == pytest.approx(
        x0 * x1 + x1 * -x0, abs=1e-6 * (1 + abs(x0 * x1))
    )


@given(st.lists(st.floats(-10, 10), min_size=1, max_size=30), st.floats(0.0, 5.0))
def test_pid_integral_stays_within_clamp(errors: list[float], clamp: float) -> None:
    pid = Pid(Gains(p=0.0, i=3.0, d=0.0, i_max=clamp, i_min=-clamp))
    for e in errors:
        assert abs(pid.compute(e, 0.01)) <= clamp + 1e-12


@given(st.lists(st.floats(-5, 5), min_size=2, max_size=50))
def test_speed_limiter_bounds_velocity_and_acceleration(targets: list[float]) -> None:
    lim = SpeedLimiter(
        has_velocity_limits=True,
        has_acceleration_limits=True,
        max_velocity=1.0,
        max_acceleration=2.0,
    )
    dt = 0.01
    v0 = v1 = 0.0
    for target in targets:
        v = lim.limit(target, v0, v1, dt)
        assert -1.0 <= v <= 1.0
        assert abs(v - v0) <= 2.0 * dt + 1e-12
        v1, v0 = v0, v
    assert not math.isnan(v0)
