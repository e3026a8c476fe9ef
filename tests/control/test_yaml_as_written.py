"""Seed 000/002's controller YAML as written: ``publish_rate: 80`` gives 80 Hz (by elapsed
time, as ROS 1's joint_state_controller limits it, not rounded to a divisor of the 100 Hz loop),
and list_controllers names the types the file names."""

from __future__ import annotations

import itertools

import pytest

from robomodel.control import ControlSystem, load_controller_config
from robomodel.control.client import ManagerClient
from robomodel.loading import load
from robomodel.runtime.clock import ManualClock
from robomodel.runtime.context import Context
from robomodel.runtime.msg import JointState
from tests.conftest import EXAMPLES

SEED_YAML = """rrbot:
  joint_state_controller:
    type: joint_state_controller/JointStateController
    publish_rate: {rate}
  joint1_position_controller:
    type: effort_controllers/JointPositionController
    joint: joint1
    pid: {{p: 100.0, i: 0.01, d: 10.0}}
  joint2_effort_controller:
    type: effort_controllers/JointEffortController
    joint: joint2
"""


def _run(rate_hz: float, seconds: float) -> tuple[list[float], ControlSystem, Context]:
    """The stamps [s] of /rrbot/joint_states over ``seconds`` of simulated time."""
    robot = load(EXAMPLES / "rrbot_description" / "urdf" / "rrbot.xacro")
    ctx = Context("inproc", clock=ManualClock())
    config = load_controller_config("rrbot.yaml", text=SEED_YAML.format(rate=rate_hz))
    system = ControlSystem.build(robot, config, context=ctx)
    stamps: list[float] = []
    probe = ctx.create_node("probe")
    probe.create_subscription(
        JointState,
        "/rrbot/joint_states",
        lambda m: stamps.append(m.header.stamp.sec + m.header.stamp.nanosec * 1e-9),
        1000,
    )
    for _ in range(round(seconds * system.manager.update_rate_hz)):
        ctx.advance(0.01)
        system.manager.step(0.01)
        ctx.spin_once()
    return stamps, system, ctx


@pytest.mark.parametrize("rate_hz", [80.0, 30.0, 7.5])
def test_publish_rate_is_honoured_by_elapsed_time(rate_hz: float) -> None:
    stamps, system, ctx = _run(rate_hz, 4.0)
    try:
        assert system.manager.update_rate_hz == 100
        measured_hz = (len(stamps) - 1) / (stamps[-1] - stamps[0])
        assert measured_hz == pytest.approx(rate_hz, abs=1.0)
        # never more often than the loop, never a gap of more than one extra loop period
        gaps = [b - a for a, b in itertools.pairwise(stamps)]
        assert min(gaps) >= 0.01 - 1e-6 and max(gaps) <= 1.0 / rate_hz + 0.01 + 1e-6
    finally:
        ctx.shutdown()


def test_list_controllers_shows_the_types_the_yaml_names() -> None:
    _stamps, system, ctx = _run(80.0, 0.05)
    try:
        manager = system.manager
        expected = {
            "joint_state_controller": "joint_state_controller/JointStateController",
            "joint1_position_controller": "effort_controllers/JointPositionController",
            "joint2_effort_controller": "effort_controllers/JointEffortController",
        }
        assert {c["name"]: c["type"] for c in manager.list_controllers()} == expected
        # robomodel runs them as its own types, which list_controllers does not show
        assert manager.entries["joint_state_controller"].type_name == (
            "joint_state_broadcaster/JointStateBroadcaster"
        )
        assert manager.entries["joint2_effort_controller"].type_name == (
            "robomodel_controllers/SingleJointForwardController"
        )
        # the controller_manager/list_controllers service (ROS 2's; ROS 1's is built from it)
        served = ManagerClient(ctx, manager.service_prefix).list_controllers()
        assert {c.name: c.type for c in served} == expected
    finally:
        ctx.shutdown()
