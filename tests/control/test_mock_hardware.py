"""mock_components/GenericSystem semantics (generic_system.cpp) and hardware from URDF."""

from __future__ import annotations

import math

import pytest

from robomodel.control.hardware import (
    GenericSystem,
    HardwareError,
    ResourceManager,
    ReturnType,
    hardware_from_robot,
)
from robomodel.description.model import Robot
from robomodel.loading import load

BASE = """<robot name="m"><link name="a"/><link name="b"/><link name="c"/>
<joint name="j1" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/>
<limit lower="-1" upper="1" effort="5" velocity="2"/></joint>
<joint name="j2" type="revolute"><parent link="b"/><child link="c"/><axis xyz="0 0 1"/>
<limit lower="-1" upper="1" effort="5" velocity="2"/><mimic joint="j1" multiplier="-2" offset="0.1"/></joint>
<ros2_control name="Mock" type="system"><hardware><plugin>mock_components/GenericSystem</plugin>
{params}</hardware>
<joint name="j1">{commands}
<state_interface name="position"><param name="initial_value">0.2</param></state_interface>
<state_interface name="velocity"/><state_interface name="acceleration"/><state_interface name="actual"/></joint>
<joint name="j2"><state_interface name="position"/><state_interface name="velocity"/></joint>
<sensor name="fts"><state_interface name="force.x"/></sensor>
</ros2_control></robot>"""

POS_VEL = '<command_interface name="position"/><command_interface name="velocity"/>'


def _rm(params: str = "", commands: str = POS_VEL) -> tuple[ResourceManager, GenericSystem]:
    robot = load(BASE.format(params=params, commands=commands))
    assert isinstance(robot, Robot)
    rm = ResourceManager(hardware_from_robot(robot))
    hw = rm.components[0]
    assert isinstance(hw, GenericSystem)
    return rm, hw


def _param(name: str, value: str) -> str:
    return f'<param name="{name}">{value}</param>'


def _s(rm: ResourceManager, name: str) -> float:
    return rm.states.values[rm.states.slot(name)]


def _c(rm: ResourceManager, name: str, value: float) -> None:
    rm.commands.values[rm.commands.slot(name, "command")] = value


def test_initial_values_nan_to_zero_and_limits() -> None:
    rm, _ = _rm()
    assert _s(rm, "j1/position") == 0.2 and _s(rm, "j1/velocity") == 0.0
    assert math.isnan(_s(rm, "fts/force.x"))  # sensors are not zeroed
    assert math.isnan(rm.commands.values[0])  # commands start NaN ("no command")
    limits = {rm.commands.names[slot]: (lo, hi) for slot, lo, hi in rm._limited}
    assert limits == {"j1/position": (-1.0, 1.0), "j1/velocity": (-2.0, 2.0)}


def test_position_follows_command_velocity_mirrors_and_mimic() -> None:
    rm, hw = _rm(_param("position_state_following_offset", "0.5"))
    assert _s(rm, "j1/position") == pytest.approx(0.7)  # configure adds the offset
    _c(rm, "j1/position", 0.3)
    _c(rm, "j1/velocity", 1.5)
    assert hw.read(0.0, 0.01) is ReturnType.OK
    assert _s(rm, "j1/position") == pytest.approx(0.8)
    assert _s(rm, "j1/velocity") == 1.5  # loopback of the same-named command
    assert _s(rm, "j2/position") == pytest.approx(0.1 - 2 * 0.8)
    assert _s(rm, "j2/velocity") == pytest.approx(-3.0)
    _c(rm, "j1/velocity", math.inf)
    assert hw.read(0.0, 0.01) is ReturnType.ERROR  # upstream: inf -> ERROR


def test_custom_interface_with_following_offset() -> None:
    rm, hw = _rm(
        _param("position_state_following_offset", "0.5")
        + _param("custom_interface_with_following_offset", "actual")
    )
    _c(rm, "j1/position", 0.3)
    hw.read(0.0, 0.01)
    assert _s(rm, "j1/position") == 0.3 and _s(rm, "j1/actual") == pytest.approx(0.8)


def test_calculate_dynamics_modes() -> None:
    rm, hw = _rm(_param("calculate_dynamics", "true"))
    assert not rm.prepare_switch(["j1/position", "j1/velocity"], [])  # two modes on a joint
    rm.perform_switch(["j1/velocity"], [])
    _c(rm, "j1/velocity", 2.0)
    hw.read(0.0, 0.1)
    assert (_s(rm, "j1/position"), _s(rm, "j1/velocity"), _s(rm, "j1/acceleration")) == (
        pytest.approx(0.4),
        2.0,
        pytest.approx(20.0),
    )
    rm.perform_switch(["j1/position"], [])
    _c(rm, "j1/position", 0.5)
    hw.read(0.0, 0.1)
    assert _s(rm, "j1/position") == 0.5 and _s(rm, "j1/velocity") == pytest.approx(1.0)


def test_acceleration_mode() -> None:
    rm, hw = _rm(
        _param("calculate_dynamics", "true"),
        commands='<command_interface name="acceleration"/>',
    )
    _c(rm, "j1/acceleration", 1.0)
    hw.read(0.0, 0.5)
    assert _s(rm, "j1/velocity") == 0.5 and _s(rm, "j1/position") == pytest.approx(0.45)


def test_mock_sensor_commands_and_disable_commands() -> None:
    rm, hw = _rm(_param("mock_sensor_commands", "true"))
    _c(rm, "fts/force.x", 3.0)
    hw.read(0.0, 0.01)
    assert _s(rm, "fts/force.x") == 3.0
    rm, hw = _rm(_param("disable_commands", "true"))
    _c(rm, "j1/position", 0.9)
    hw.read(0.0, 0.01)
    assert _s(rm, "j1/position") == 0.2


def test_hardware_errors() -> None:
    bad_joint = BASE.format(params="", commands=POS_VEL).replace(
        '<joint name="j1">', '<joint name="j9">'
    )
    with pytest.raises(HardwareError, match="'j9' is not in the URDF"):
        hardware_from_robot(load(bad_joint))  # type: ignore[arg-type]
    bad_plugin = BASE.format(params="", commands=POS_VEL).replace(
        "mock_components/GenericSystem", "mock_components/GenericSystm"
    )
    with pytest.raises(HardwareError, match="did you mean 'mock_components/GenericSystem'"):
        hardware_from_robot(load(bad_plugin))  # type: ignore[arg-type]
    mimic_cmd = BASE.format(params="", commands=POS_VEL).replace(
        '<joint name="j2">', '<joint name="j2"><command_interface name="position"/>'
    )
    with pytest.raises(HardwareError, match="mimic joint 'j2' may not have command"):
        hardware_from_robot(load(mimic_cmd))  # type: ignore[arg-type]
    bad_number = BASE.format(params="", commands=POS_VEL).replace(
        '<param name="initial_value">0.2</param>', '<param name="initial_value">zero</param>'
    )
    with pytest.raises(HardwareError, match="initial_value of j1/position must be a number"):
        hardware_from_robot(load(bad_number))  # type: ignore[arg-type]


def test_hardware_failure_deactivates_its_controllers() -> None:
    from robomodel.control import ControllerManager
    from robomodel.control.controllers import ControllerState

    robot = load(BASE.format(params="", commands=POS_VEL))
    rm = ResourceManager(hardware_from_robot(robot))  # type: ignore[arg-type]
    cm = ControllerManager(rm, robot=robot)  # type: ignore[arg-type]
    fwd = cm.load_controller(
        "v", "velocity_controllers/JointGroupVelocityController", {"joints": ["j1"]}
    )
    cm.spawn(["v"])
    _c(rm, "j1/velocity", math.inf)  # bypasses the controller: the hardware read fails
    rm._last_good[rm.commands.slot("j1/velocity")] = math.inf
    cm.read(0.0, 0.01)
    assert fwd.state is ControllerState.INACTIVE


PENDULUM = """<robot name="p"><link name="base"/>
<link name="bob"><inertial><origin xyz="0 0 -1"/><mass value="1"/>
<inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/></inertial></link>
<joint name="j" type="continuous"><parent link="base"/><child link="bob"/><axis xyz="0 1 0"/></joint>
<ros2_control name="P" type="system"><hardware><plugin>mock_components/GenericSystem</plugin>
<param name="calculate_dynamics">true</param></hardware>
<joint name="j"><command_interface name="effort"/>
<state_interface name="position"><param name="initial_value">0.05</param></state_interface>
<state_interface name="velocity"/><state_interface name="effort"/></joint>
</ros2_control></robot>"""


def test_effort_integration_swings_a_pendulum_with_the_right_period() -> None:
    robot = load(PENDULUM)
    rm = ResourceManager(hardware_from_robot(robot))  # type: ignore[arg-type]
    hw = rm.components[0]
    _c(rm, "j/effort", 0.0)
    crossings: list[float] = []
    last = _s(rm, "j/position")
    for k in range(1, 4001):  # 4 s at 1 ms
        hw.read(k * 0.001, 0.001)
        now = _s(rm, "j/position")
        if last > 0.0 >= now or last < 0.0 <= now:
            crossings.append(k * 0.001)
        last = now
    period = 2 * (crossings[2] - crossings[1])
    assert period == pytest.approx(2 * math.pi * math.sqrt(1.0 / 9.81), rel=0.01)
