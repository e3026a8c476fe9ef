"""Input from other processes is parsed strictly and never costs good messages."""

from __future__ import annotations

import logging
import math
from pathlib import Path

import pytest

from tests.conftest import importorskip_mujoco, unique_domain
from tests.timing import scaled


def test_a_bad_attachment_costs_no_other_message(caplog: pytest.LogCaptureFixture) -> None:
    """Samples from a peer without rmw_zenoh's attachment are dropped (as rmw_zenoh drops
    them) with one warning, and the good samples around them are delivered."""
    from robomodel.runtime import Context
    from robomodel.runtime.msg import Float64, serialize
    from robomodel.runtime.transport.rmw_zenoh import encode_attachment

    domain = int(unique_domain())
    got: list[float] = []
    with Context("zenoh", domain_id=domain) as ctx:
        ctx.create_node("sub").create_subscription(
            Float64, "/chatter", lambda m: got.append(m.data)
        )
        transport = ctx.transport
        session = transport.session  # type: ignore[attr-defined]
        key = transport.data_key("/chatter", Float64)  # type: ignore[attr-defined]
        gid = bytes(range(16))
        with caplog.at_level(logging.WARNING, logger="robomodel.runtime"):
            # One batch: bad samples first, then good ones from a (foreign) publisher GID.
            session.put(key, serialize(Float64(-1.0)), attachment="std_msgs/msg/Float64|x|1")
            session.put(key, serialize(Float64(-2.0)))  # no attachment at all
            for n in range(1, 6):
                attachment = encode_attachment(n, 0, gid)
                session.put(key, serialize(Float64(float(n))), attachment=attachment)
            session.put(key, b"\x00\x01\x00\x00\x01", attachment=encode_attachment(6, 0, gid))
            ctx.spin(duration_s=scaled(5.0), until=lambda: len(got) >= 5)
            ctx.spin(duration_s=0.3)
        for n in range(1000):
            transport.warn_once(("flood", str(n)), "flood %s", n)  # type: ignore[attr-defined]
        assert len(transport._warned) <= 256  # type: ignore[attr-defined]
    assert got == [1.0, 2.0, 3.0, 4.0, 5.0]
    missing = [r for r in caplog.records if "valid rmw_zenoh attachment" in r.getMessage()]
    assert len(missing) == 1
    assert len([r for r in caplog.records if "malformed" in r.getMessage()]) == 1
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
    importorskip_mujoco()
    from robomodel.description.urdf.reader import read_urdf
    from robomodel.runtime import Context, ManualClock
    from robomodel.runtime.msg.types.std_msgs import Float64MultiArray
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
