"""Small robots and systems for the control tests."""

from __future__ import annotations

from typing import Any

from robomodel.control import ControllerManager
from robomodel.control.controllers import DiffDriveController
from robomodel.control.hardware import LoanedInterface, ResourceManager, hardware_from_robot
from robomodel.description.model import Robot
from robomodel.loading import load

WHEELS = """<robot name="base"><link name="base_link"/>
<link name="l"/><link name="r"/><link name="l2"/><link name="r2"/>
<joint name="left_wheel" type="continuous"><parent link="base_link"/><child link="l"/></joint>
<joint name="right_wheel" type="continuous"><parent link="base_link"/><child link="r"/></joint>
<joint name="left_wheel2" type="continuous"><parent link="base_link"/><child link="l2"/></joint>
<joint name="right_wheel2" type="continuous"><parent link="base_link"/><child link="r2"/></joint>
<ros2_control name="Base" type="system"><hardware><plugin>mock_components/GenericSystem</plugin>
<param name="calculate_dynamics">true</param></hardware>
{joints}
</ros2_control></robot>"""

WHEEL = """<joint name="{name}"><command_interface name="velocity"/>
<state_interface name="position"/><state_interface name="velocity"/></joint>"""

ARM = """<robot name="arm"><link name="base_link"/>
<link name="l1"><inertial><origin xyz="0.5 0 0"/><mass value="1"/>
<inertia ixx="0.01" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial></link>
<link name="l2"><inertial><origin xyz="0.5 0 0"/><mass value="1"/>
<inertia ixx="0.01" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial></link>
<joint name="joint1" type="revolute"><parent link="base_link"/><child link="l1"/>
<axis xyz="0 0 1"/><limit lower="-2" upper="2" effort="50" velocity="3"/></joint>
<joint name="joint2" type="revolute"><parent link="l1"/><child link="l2"/>
<origin xyz="1 0 0"/><axis xyz="0 0 1"/><limit lower="-2" upper="2" effort="50" velocity="3"/></joint>
<ros2_control name="Arm" type="system"><hardware><plugin>mock_components/GenericSystem</plugin></hardware>
<joint name="joint1"><command_interface name="position"><param name="min">-1</param><param name="max">1</param></command_interface>
<command_interface name="velocity"/>
<state_interface name="position"><param name="initial_value">0.25</param></state_interface><state_interface name="velocity"/></joint>
<joint name="joint2"><command_interface name="position"/><command_interface name="velocity"/>
<state_interface name="position"/><state_interface name="velocity"/></joint>
</ros2_control></robot>"""


def arm() -> Robot:
    robot = load(ARM)
    assert isinstance(robot, Robot)
    return robot


def arm_manager(**kwargs: Any) -> ControllerManager:
    robot = arm()
    return ControllerManager(ResourceManager(hardware_from_robot(robot)), robot=robot, **kwargs)


def diff_drive_system(
    params: dict[str, Any], wheels_per_side: int = 1
) -> tuple[ControllerManager, DiffDriveController, list[LoanedInterface]]:
    names = ["left_wheel", "right_wheel", "left_wheel2", "right_wheel2"][: 2 * wheels_per_side]
    robot = load(WHEELS.format(joints="".join(WHEEL.format(name=n) for n in names)))
    assert isinstance(robot, Robot)
    rm = ResourceManager(hardware_from_robot(robot))
    cm = ControllerManager(rm, robot=robot, update_rate_hz=1000)
    left = names[0::2]
    right = names[1::2]
    cm.load_controller(
        "dd",
        "diff_drive_controller/DiffDriveController",
        {"left_wheel_names": left, "right_wheel_names": right, **params},
    )
    cm.configure_controller("dd")
    cm.switch_controllers(activate=["dd"])
    ctrl = cm.entries["dd"].controller
    assert isinstance(ctrl, DiffDriveController)
    wheels = [LoanedInterface(rm.commands, f"{n}/velocity", "command") for n in names]
    return cm, ctrl, wheels
