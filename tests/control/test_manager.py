"""Controller manager: lifecycle, switch rules, claiming, rates, fallback, bad commands."""

from __future__ import annotations

import logging
import math

import pytest

from robomodel.control import ControlError, ControllerStateError, Strictness, UnknownControllerError
from robomodel.control.controllers import ControllerState, UnknownControllerTypeError
from robomodel.control.hardware import InterfaceClaimedError, UnknownInterfaceError
from tests.control.helpers import arm_manager

FCC = "forward_command_controller/ForwardCommandController"
POS = {"joints": ["joint1", "joint2"], "interface_name": "position"}


def test_lifecycle_states_and_rules() -> None:
    cm = arm_manager()
    c = cm.load_controller("fwd", FCC, POS)
    assert c.state is ControllerState.UNCONFIGURED
    with pytest.raises(ControlError, match="unconfigured"):
        cm.switch_controllers(activate=["fwd"])
    cm.configure_controller("fwd")
    assert c.state is ControllerState.INACTIVE
    cm.switch_controllers(activate=["fwd"])
    assert c.state is ControllerState.ACTIVE
    assert cm.resources.claimed == {"joint1/position": "fwd", "joint2/position": "fwd"}
    with pytest.raises(ControllerStateError):
        cm.configure_controller("fwd")
    with pytest.raises(ControllerStateError, match="deactivate"):
        cm.unload_controller("fwd")
    cm.switch_controllers(deactivate=["fwd"])
    assert c.state is ControllerState.INACTIVE and not cm.resources.claimed
    cm.cleanup_controller("fwd")
    assert c.state is ControllerState.UNCONFIGURED
    cm.unload_controller("fwd")
    assert c.state is ControllerState.FINALIZED and "fwd" not in cm.entries
    with pytest.raises(UnknownControllerError):
        cm.configure_controller("fwd")


def test_duplicate_and_unknown_type() -> None:
    cm = arm_manager()
    cm.load_controller("fwd", FCC, POS)
    with pytest.raises(ControlError, match="already loaded"):
        cm.load_controller("fwd", FCC, POS)
    with pytest.raises(UnknownControllerTypeError, match="did you mean"):
        cm.load_controller("x", "forward_command_controller/ForwardCommandControler")


def test_claiming_conflicts_strict_and_best_effort() -> None:
    cm = arm_manager()
    cm.load_controller("a", FCC, POS)
    cm.load_controller("b", FCC, {"joints": ["joint1"], "interface_name": "position"})
    cm.load_controller("bad", FCC, {"joints": ["joint1"], "interface_name": "torque"})
    for n in ("a", "b", "bad"):
        cm.configure_controller(n)
    cm.switch_controllers(activate=["a"])
    with pytest.raises(ControlError, match="claimed by controller 'a'"):
        cm.switch_controllers(activate=["b"])
    with pytest.raises(ControlError, match="joint1/torque"):
        cm.switch_controllers(activate=["bad"])
    # STRICT: an unknown name aborts the whole request
    with pytest.raises(ControlError):
        cm.switch_controllers(activate=["b"], deactivate=["a", "nope"])
    assert cm.entries["a"].controller.state is ControllerState.ACTIVE
    # BEST_EFFORT drops the bad entries and does the rest
    cm.switch_controllers(
        activate=["b", "nope"], deactivate=["a"], strictness=Strictness.BEST_EFFORT
    )
    assert cm.entries["b"].controller.state is ControllerState.ACTIVE
    assert cm.entries["a"].controller.state is ControllerState.INACTIVE
    # both in one request claiming the same interface
    cm.switch_controllers(deactivate=["b"])
    with pytest.raises(ControlError, match="both claim"):
        cm.switch_controllers(activate=["a", "b"])
    # restart (deactivate + activate in one request)
    cm.switch_controllers(activate=["a"])
    cm.switch_controllers(activate=["a"], deactivate=["a"])
    assert cm.entries["a"].controller.state is ControllerState.ACTIVE


def test_resource_manager_errors() -> None:
    cm = arm_manager()
    rm = cm.resources
    rm.claim(["joint1/position"], "x")
    with pytest.raises(InterfaceClaimedError, match="already claimed by controller 'x'"):
        rm.claim(["joint1/position"], "y")
    with pytest.raises(UnknownInterfaceError, match="did you mean"):
        rm.claim(["joint1/positon"], "y")


def test_mock_follows_commands_initial_values_and_limits(caplog: pytest.LogCaptureFixture) -> None:
    cm = arm_manager()
    rm = cm.resources
    assert rm.states.values[rm.states.slot("joint1/position")] == 0.25  # initial_value
    fwd = cm.load_controller("fwd", FCC, POS)
    cm.configure_controller("fwd")
    cm.switch_controllers(activate=["fwd"])
    fwd.set_command([0.5, -0.3])  # type: ignore[attr-defined]
    cm.step()
    cm.step()
    assert rm.states.values[rm.states.slot("joint1/position")] == 0.5
    assert rm.states.values[rm.states.slot("joint2/position")] == -0.3
    with caplog.at_level(logging.WARNING, logger="robomodel.control"):
        fwd.set_command([3.0, 5.0])  # type: ignore[attr-defined]
        cm.step()
        cm.step()
    # <param max=1> tightens the URDF limit 2 for joint1; joint2 keeps the URDF's 2
    assert rm.commands.values[rm.commands.slot("joint1/position")] == 1.0
    assert rm.commands.values[rm.commands.slot("joint2/position")] == 2.0
    assert sum("outside its limits" in r.message for r in caplog.records) == 2  # once each
    caplog.clear()
    with caplog.at_level(logging.WARNING, logger="robomodel.control"):
        fwd.set_command([math.nan, 0.0])  # type: ignore[attr-defined]
        cm.step()
    assert any("not finite" in r.message for r in caplog.records)
    assert rm.commands.values[rm.commands.slot("joint1/position")] == 1.0  # last good held
    caplog.clear()
    with caplog.at_level(logging.WARNING, logger="robomodel.control"):
        for _ in range(20):  # chattering at the limit: out, in, out, ...
            fwd.set_command([3.0, 0.0])  # type: ignore[attr-defined]
            cm.step()
            fwd.set_command([0.0, 0.0])  # type: ignore[attr-defined]
            cm.step()
    counts = [r.getMessage() for r in caplog.records if "joint1/position" in r.getMessage()]
    # throttled: entries 2, 3, 5, 9, 17 of joint1 (the 1st was above), each with its count
    assert [m.rsplit("(", 1)[1] for m in counts] == [
        "2 times)",
        "3 times)",
        "5 times)",
        "9 times)",
        "17 times)",
    ]


def test_non_finite_hardware_command_holds_last_good(caplog: pytest.LogCaptureFixture) -> None:
    cm = arm_manager()
    rm = cm.resources
    slot = rm.commands.slot("joint2/velocity")
    rm.commands.values[slot] = 0.5
    cm.step()
    with caplog.at_level(logging.WARNING, logger="robomodel.control"):
        for _ in range(5):
            rm.commands.values[slot] = math.inf
            cm.step()
    assert rm.commands.values[slot] == 0.5
    assert (
        sum("not finite" in r.message for r in caplog.records) == 4
    )  # throttled: the 1st, 2nd, 3rd and 5th time


def test_error_deactivates_and_activates_fallback() -> None:
    cm = arm_manager()
    fwd = cm.load_controller("fwd", FCC, {**POS, "fallback_controllers": ["hold"]})
    cm.load_controller("hold", FCC, {"joints": ["joint1", "joint2"], "interface_name": "velocity"})
    cm.spawn(["fwd"])
    cm.spawn(["hold"], activate=False)
    fwd.set_command([0.1])  # type: ignore[attr-defined]  # wrong length -> ERROR
    cm.step()
    assert fwd.state is ControllerState.INACTIVE
    assert cm.entries["hold"].controller.state is ControllerState.ACTIVE


def _ok() -> object:
    from robomodel.control.hardware import ReturnType

    return ReturnType.OK


def test_per_controller_rate() -> None:
    cm = arm_manager(update_rate_hz=100)
    c = cm.load_controller("fwd", FCC, {**POS, "update_rate": 25})
    calls: list[float] = []
    original = c.update
    c.update = lambda t, p: (calls.append(p), original(t, p))[1]  # type: ignore[method-assign]
    cm.spawn(["fwd"])
    for _ in range(8):
        cm.step()
    assert calls == pytest.approx([0.04, 0.04])
    c3 = cm.load_controller(
        "odd", FCC, {"joints": ["joint1"], "interface_name": "velocity", "update_rate": 30}
    )
    assert c3.update_rate_hz == 33  # 100 // round(100 / 30)
    runs: list[int] = []
    c3.update = lambda t, p: (runs.append(cm._counter), _ok())[1]  # type: ignore[method-assign]
    cm.spawn(["odd"])
    for _ in range(100):
        cm.step()
    # humble: run when (counter % 100) % 3 == 0 -> 99, 100 (wraps to 0), 102, ...
    assert runs[:3] == [9, 12, 15] and 100 in runs and 99 in runs
    assert cm.load_controller("fast", FCC, {**POS, "update_rate": 500}).update_rate_hz == 100


def test_best_effort_drops_a_controller_without_reserving_its_interfaces() -> None:
    """A controller dropped from a BEST_EFFORT request (one of its interfaces is missing)
    claims nothing: another controller of the same request may take what it would have."""
    cm = arm_manager()
    cm.load_controller("wide", FCC, {"joints": ["joint1", "joint9"], "interface_name": "position"})
    cm.load_controller("b", FCC, {"joints": ["joint1"], "interface_name": "position"})
    for n in ("wide", "b"):
        cm.configure_controller(n)
    with pytest.raises(ControlError, match="joint9/position"):
        cm.switch_controllers(activate=["wide", "b"])
    cm.switch_controllers(activate=["wide", "b"], strictness=Strictness.BEST_EFFORT)
    assert cm.entries["wide"].controller.state is ControllerState.INACTIVE
    assert cm.entries["b"].controller.state is ControllerState.ACTIVE
    assert cm.resources.claimed.get("joint1/position") == "b"
