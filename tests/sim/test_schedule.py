"""The stepping schedule: callbacks at their steps, and the stretches between them handed to
MuJoCo in one ``mj_step(nstep=k)`` call with the same result as single steps."""

from __future__ import annotations

import pytest

from robomodel.sim.schedule import ScheduledCallback, StepSchedule
from tests.sim.conftest import EXAMPLES

mujoco = pytest.importorskip("mujoco")


def test_steps_to_next_due_is_the_nearest_multiple_of_any_interval() -> None:
    schedule = StepSchedule()
    assert schedule.steps_to_next_due(7) > 10**6  # nothing scheduled: no bound from here
    schedule.add(ScheduledCallback(10, lambda t: None))
    schedule.add(ScheduledCallback(4, lambda t: None))
    assert not schedule.runs_every_step
    # after step 0 the next due steps are 4, 8, 10, 12, 16, 20
    assert [schedule.steps_to_next_due(s) for s in (0, 3, 4, 8, 9, 10, 11)] == [4, 1, 4, 2, 1, 2, 1]


def test_callbacks_run_at_their_steps_in_order_then_registration() -> None:
    schedule = StepSchedule()
    calls: list[tuple[str, int]] = []
    step = [0]
    schedule.add(ScheduledCallback(2, lambda t: calls.append(("sensor", step[0])), order=1))
    schedule.add(ScheduledCallback(3, lambda t: calls.append(("manager", step[0])), order=0))
    schedule.add(ScheduledCallback(2, lambda t: calls.append(("tick", step[0])), order=-1))
    for s in range(7):
        step[0] = s
        schedule.run_due(s, 0.0)
    assert calls == [
        ("tick", 0), ("manager", 0), ("sensor", 0),
        ("tick", 2), ("sensor", 2),
        ("manager", 3),
        ("tick", 4), ("sensor", 4),
        ("tick", 6), ("manager", 6), ("sensor", 6),
    ]  # fmt: skip
    assert not schedule.runs_every_step
    schedule.add(ScheduledCallback(1, lambda t: None))
    assert schedule.runs_every_step
    with pytest.raises(ValueError, match="every_steps"):
        schedule.add(ScheduledCallback(0, lambda t: None))


def test_batched_stepping_equals_single_steps_bit_for_bit() -> None:
    """A state-feedback callback every 7 steps (a PD torque written into qfrc_applied) through
    ``Simulation.step`` equals the same callback in a loop of single ``mj_step`` calls."""
    from robomodel.loading import load
    from robomodel.sim import Simulation

    robot = load(str(EXAMPLES / "rrbot_description/urdf/rrbot.xacro"))
    sim = Simulation()
    sim.add_robot(robot)
    model = sim.model
    ref = mujoco.MjData(model)
    ref.qpos[:] = sim.data.qpos
    start = ref.qpos.copy()
    mujoco.mj_forward(model, ref)
    seen: list[float] = []

    def pd(data):  # type: ignore[no-untyped-def]
        def control(time_s: float) -> None:
            data.qfrc_applied[:] = -30.0 * (data.qpos - 0.4) - 2.0 * data.qvel
            if data is sim.data:
                seen.append(time_s)

        return control

    sim.every(1.0 / (7 * sim.timestep_s), pd(sim.data))
    sim.step(250)
    reference = pd(ref)
    for s in range(250):
        if s % 7 == 0:
            reference(ref.time)
        mujoco.mj_step(model, ref)
    assert len(seen) == 36  # steps 0, 7, ..., 245
    assert seen[1] == pytest.approx(7 * sim.timestep_s)
    assert sim.data.time == ref.time
    assert (sim.data.qpos == ref.qpos).all() and (sim.data.qvel == ref.qvel).all()
    assert abs(sim.data.qpos - start).min() > 0.05  # the arm moved: not a trivial equality


def test_a_gated_callback_runs_and_shortens_the_stretches_only_while_active() -> None:
    schedule = StepSchedule()
    active = [False]
    calls: list[int] = []
    step = [0]
    schedule.add(ScheduledCallback(10, lambda t: None))
    schedule.add(ScheduledCallback(1, lambda t: calls.append(step[0]), active=lambda: active[0]))
    assert not schedule.runs_every_step  # gated: not for good
    assert schedule.steps_to_next_due(3) == 7  # inactive: the whole stretch to step 10
    for step[0] in range(5):
        schedule.run_due(step[0], 0.0)
    assert calls == []
    active[0] = True
    assert schedule.steps_to_next_due(3) == 1
    for step[0] in range(5, 8):
        schedule.run_due(step[0], 0.0)
    assert calls == [5, 6, 7]
