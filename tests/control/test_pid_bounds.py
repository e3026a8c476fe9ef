"""PID bounds checked as control_toolbox checks them.

Transcribed from control_toolbox's test/pid_tests.cpp:
- ``ITermBadIBoundsTestConstructor`` (Humble): ``Pid(1.0, 1.0, 1.0, -1.0, 1.0)`` (i_max=-1 <
  i_min=1) throws ``std::invalid_argument``;
- ``ITermBadIBoundsTest``: ``setGains`` with i_min > i_max keeps the previous gains;
- ``UTermBadIBoundsTestConstructor`` (master): u_min > u_max throws.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from robomodel.control.config import load_controller_config
from robomodel.control.exceptions import ConfigError
from robomodel.control.pid import Gains, Pid, PidBoundsError, PidKilted


def test_humble_constructor_refuses_i_min_above_i_max() -> None:
    with pytest.raises(PidBoundsError, match=r"i_min > i_max \(i_min=1, i_max=-1\)"):
        Pid(Gains(p=1.0, i=1.0, d=1.0, i_max=-1.0, i_min=1.0))
    with pytest.raises(ValueError):  # invalid_argument's Python counterpart
        Pid(Gains(p=1.0, i=1.0, d=1.0, i_max=-1.0, i_min=1.0))


def test_humble_set_gains_keeps_the_old_gains() -> None:
    pid = Pid(Gains(p=1.0, i=1.0, d=1.0, i_max=1.0, i_min=-1.0))
    with pytest.warns(RuntimeWarning) as warned:
        taken = pid.set_gains(Gains(p=2.0, i=2.0, d=2.0, i_max=-1.0, i_min=1.0))
    assert taken is False
    assert [str(w.message) for w in warned] == [
        "received i_min > i_max (i_min=1, i_max=-1), skip new gains"
    ]
    assert not warned[0].filename.endswith("pid.py")  # the caller's line, not the library's
    assert pid.gains == Gains(p=1.0, i=1.0, d=1.0, i_max=1.0, i_min=-1.0)
    assert pid.set_gains(Gains(p=2.0, i_max=1.0, i_min=1.0)) is True  # equal bounds are valid
    assert pid.gains.p == 2.0


def test_kilted_constructor_refuses_u_min_above_u_max() -> None:
    with pytest.raises(PidBoundsError, match=r"u_min > u_max \(u_min=1, u_max=-1\)"):
        PidKilted(1.0, 1.0, 1.0, u_clamp_max=-1.0, u_clamp_min=1.0)
    with pytest.raises(PidBoundsError, match="i_min > i_max"):
        PidKilted(1.0, 1.0, 1.0, i_clamp_max=-1.0, i_clamp_min=1.0)
    PidKilted(1.0, 1.0, 1.0, u_clamp_max=1.0, u_clamp_min=-1.0)


@pytest.mark.parametrize(
    ("text", "line", "column", "what"),
    [
        (  # ROS 1 layout (seed 000's rrbot_control.yaml with a bad clamp)
            "rrbot:\n"
            "  joint1_position_controller:\n"
            "    type: effort_controllers/JointPositionController\n"
            "    joint: joint1\n"
            "    pid: {p: 100.0, i: 0.01, d: 10.0, i_clamp_min: 5, i_clamp_max: -5}\n",
            5,
            39,
            "i_clamp_min=5 > i_clamp_max=-5",
        ),
        (  # ROS 2 layout, gains per joint of a JTC
            "controller_manager:\n"
            "  ros__parameters:\n"
            "    update_rate: 100\n"
            "    jtc:\n"
            "      type: joint_trajectory_controller/JointTrajectoryController\n"
            "jtc:\n"
            "  ros__parameters:\n"
            "    joints: [joint1]\n"
            "    command_interfaces: [effort]\n"
            "    state_interfaces: [position, velocity]\n"
            "    gains:\n"
            "      joint1:\n"
            "        p: 10.0\n"
            "        u_clamp_max: -2.0\n"
            "        u_clamp_min: 2.0\n",
            15,
            9,
            "u_clamp_min=2 > u_clamp_max=-2",
        ),
    ],
)
def test_yaml_with_bad_bounds_is_refused_at_its_line(
    tmp_path: Path, text: str, line: int, column: int, what: str
) -> None:
    path = tmp_path / "controllers.yaml"
    path.write_text(text)
    with pytest.raises(ConfigError) as info:
        load_controller_config(path)
    assert info.value.location is not None
    assert (info.value.location.line, info.value.location.column) == (line, column)
    assert what in info.value.message
