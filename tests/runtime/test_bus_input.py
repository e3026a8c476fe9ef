"""Issue 15.10: input from other processes is parsed strictly and never costs good messages."""

from __future__ import annotations

import logging
import math
from pathlib import Path

import pytest

from robomodel.runtime.transport._attachment import SequenceFilter, parse_attachment
from tests.conftest import unique_domain


@pytest.mark.parametrize(
    "raw",
    [
        "std_msgs/msg/Float64|x|²".encode(),  # '²'.isdigit() is True, int('²') raises
        "std_msgs/msg/Float64|x|١٢".encode(),  # Arabic-Indic digits: int() accepts, we do not
        "std_msgs/msg/Flöat64|x|1".encode(),
        b"std_msgs/msg/Float64|x|1|extra",
        b"std_msgs/msg/Float64|x|" + b"9" * 20,  # beyond int64
        b"std_msgs/msg/Float64||1",
        b"\xff\xfe|x|1",
        b"",
    ],
)
def test_malformed_attachments_are_refused(raw: bytes) -> None:
    assert parse_attachment(raw) is None


def test_a_good_attachment_parses() -> None:
    parsed = parse_attachment(b"std_msgs/msg/Float64|3fa2c9|42")
    assert parsed is not None
    assert (parsed.type_name, parsed.publisher_id, parsed.sequence) == (
        "std_msgs/msg/Float64",
        "3fa2c9",
        42,
    )


def test_sequence_state_is_bounded_when_ids_flood() -> None:
    seen = SequenceFilter(max_publishers=64)
    for i in range(10_000):
        assert seen.accept(f"forged{i}", 1)
    assert len(seen) == 64


def test_a_forged_huge_sequence_does_not_silence_the_real_publisher() -> None:
    seen = SequenceFilter()
    assert [seen.accept("real", n) for n in (1, 2, 3)] == [True, True, True]
    assert not seen.accept("real", 3)  # a history replay of the last sample
    assert seen.accept("real", 10**18)  # a peer forging the real publisher's id
    delivered = [seen.accept("real", n) for n in (4, 5, 6)]
    assert delivered == [True, True, True]
    assert not seen.accept("real", 6)


def test_a_bad_attachment_costs_no_other_message(caplog: pytest.LogCaptureFixture) -> None:
    from robomodel.runtime import Context
    from robomodel.runtime.msg import Float64, serialize

    domain = int(unique_domain())
    got: list[float] = []
    with Context("zenoh", domain_id=domain) as ctx:
        ctx.create_node("sub").create_subscription(
            Float64, "/chatter", lambda m: got.append(m.data)
        )
        session = ctx.transport.session  # type: ignore[attr-defined]
        key = f"rm/{domain}/t/chatter"
        with caplog.at_level(logging.WARNING, logger="robomodel.runtime"):
            # One batch: the bad sample first, then good ones from a (foreign) publisher id.
            session.put(key, serialize(Float64(-1.0)), attachment="std_msgs/msg/Float64|x|²")
            for n in range(1, 6):
                attachment = f"std_msgs/msg/Float64|peer|{n}"
                session.put(key, serialize(Float64(float(n))), attachment=attachment)
            ctx.spin(duration_s=5.0, until=lambda: len(got) >= 5)
            for n in range(6, 10):  # flood of distinct type names: warnings stay bounded
                session.put(key, b"x", attachment=f"t{n}/msg/X|p|1")
            ctx.spin(duration_s=0.5)
        transport = ctx.transport
        for n in range(1000):
            transport.warn_once(("flood", str(n)), "flood %s", n)  # type: ignore[attr-defined]
        assert len(transport._warned) <= 256  # type: ignore[attr-defined]
    assert got == [1.0, 2.0, 3.0, 4.0, 5.0]
    malformed = [r for r in caplog.records if "malformed attachment" in r.getMessage()]
    assert len(malformed) == 1
    assert not [r for r in caplog.records if r.exc_info]


def test_diff_drive_refuses_non_finite_and_huge_commands(caplog: pytest.LogCaptureFixture) -> None:
    from robomodel.control.controllers import DiffDriveController
    from robomodel.runtime import Context, ManualClock

    ctx = Context("inproc", clock=ManualClock())
    c = DiffDriveController()
    c.init(
        "dd",
        {
            "left_wheel_names": ["l"],
            "right_wheel_names": ["r"],
            "wheel_separation": 1.0,
            "wheel_radius": 0.1,
        },
        node=ctx.create_node("dd"),
    )
    c.on_configure()
    c.set_command(0.3, 0.1)
    with caplog.at_level(logging.WARNING, logger="robomodel.control"):
        for bad in ((math.nan, 0.0), (0.0, math.inf), (1e300, 0.0), (0.0, -2e6)):
            c.set_command(*bad)
    assert c.command[:2] == (0.3, 0.1)  # the last good command is held
    warned = [r.getMessage() for r in caplog.records if "cmd_vel" in r.getMessage()]
    assert len(warned) == 3 and "(4 times)" in warned[-1]  # at the 1st, 2nd and 4th refusal
    ctx.shutdown()


def test_simulated_hardware_clamps_huge_velocity_before_mujoco(tmp_path: Path) -> None:
    pytest.importorskip("mujoco")
    from robomodel.description.urdf.reader import read_urdf
    from robomodel.runtime import Context, ManualClock
    from robomodel.runtime.msg.std_msgs import Float64MultiArray
    from robomodel.sim import Simulation
    from robomodel.sim.bus import SimBridge
    from robomodel.sim.hardware import MAX_VELOCITY_COMMAND
    from tests.sim.test_ros2_control import URDF, YAML

    config = tmp_path / "controllers.yaml"
    config.write_text(YAML)
    context = Context(clock=ManualClock())
    sim = Simulation(world=None)
    sim.add_robot(read_urdf(URDF.encode(), path="arm.urdf").robot)
    sim.control(config, context=context)
    SimBridge(sim, context)
    spin = context.create_node("test").create_publisher(
        Float64MultiArray, "/spin_controller/commands"
    )
    spin.publish(Float64MultiArray(data=[1e300]))  # finite, far beyond anything physical
    with pytest.warns(UserWarning, match="clamped to"):
        sim.step(200)
    assert float(abs(sim.data.ctrl).max()) == MAX_VELOCITY_COMMAND
    assert sim.data.warning[mujoco_warning_ctrl()].number == 0
    context.shutdown()


def mujoco_warning_ctrl() -> int:
    import mujoco

    return int(mujoco.mjtWarning.mjWARN_BADCTRL)
