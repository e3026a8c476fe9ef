"""ROS 2 path: <ros2_control> with gazebo_ros2_control/GazeboSystem, ROS 2 YAML, topics."""

from __future__ import annotations

import pytest

from robomodel.description.urdf.reader import read_urdf
from robomodel.runtime import Context, ManualClock
from robomodel.runtime.msg.types.sensor_msgs import JointState
from robomodel.runtime.msg.types.std_msgs import Float64MultiArray
from robomodel.sim import Simulation
from robomodel.sim.bus import SimBridge

INERTIAL = (
    '<inertial><origin xyz="0.25 0 0"/><mass value="1"/>'
    '<inertia ixx="0.001" iyy="0.02" izz="0.02" ixy="0" ixz="0" iyz="0"/></inertial>'
)
URDF = f"""<robot name="arm">
  <link name="world"/>
  <link name="base"/>
  <joint name="fix" type="fixed"><parent link="world"/><child link="base"/></joint>
  <link name="a">{INERTIAL}</link>
  <link name="b">{INERTIAL}</link>
  <joint name="spin" type="continuous"><parent link="base"/><child link="a"/><axis xyz="0 0 1"/>
    <dynamics damping="0.1"/></joint>
  <joint name="lift" type="revolute"><parent link="a"/><child link="b"/><origin xyz="0.5 0 0"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="5" velocity="2"/></joint>
  <ros2_control name="GazeboSystem" type="system">
    <hardware><plugin>gazebo_ros2_control/GazeboSystem</plugin></hardware>
    <joint name="spin">
      <command_interface name="velocity"/>
      <state_interface name="position"/><state_interface name="velocity"/>
    </joint>
    <joint name="lift">
      <command_interface name="position"/>
      <state_interface name="position"><param name="initial_value">0.5</param></state_interface>
      <state_interface name="velocity"/>
    </joint>
  </ros2_control>
</robot>"""

YAML = """controller_manager:
  ros__parameters:
    update_rate: 200
    joint_state_broadcaster:
      type: joint_state_broadcaster/JointStateBroadcaster
    spin_controller:
      type: velocity_controllers/JointGroupVelocityController
    lift_controller:
      type: position_controllers/JointGroupPositionController
spin_controller:
  ros__parameters:
    joints: [spin]
lift_controller:
  ros__parameters:
    joints: [lift]
"""


def test_gazebo_system_velocity_and_position_joints_over_topics(tmp_path) -> None:  # type: ignore[no-untyped-def]
    config = tmp_path / "controllers.yaml"
    config.write_text(YAML)
    context = Context(clock=ManualClock())
    sim = Simulation(world=None)
    sim.add_robot(read_urdf(URDF.encode(), path="arm.urdf").robot)
    system = sim.control(config, context=context)
    assert type(system.resources.components[0]).__name__ == "SimSystem"
    assert sim.data.joint("lift").qpos[0] == pytest.approx(0.5)  # initial_value
    SimBridge(sim, context)
    node = context.create_node("test")
    states: list[JointState] = []
    node.create_subscription(JointState, "/joint_states", states.append)
    spin = node.create_publisher(Float64MultiArray, "/spin_controller/commands")
    lift = node.create_publisher(Float64MultiArray, "/lift_controller/commands")
    spin.publish(Float64MultiArray(data=[1.5]))
    lift.publish(Float64MultiArray(data=[3.0]))  # beyond the limit: clamped to 1.0
    sim.step(2000)
    assert sim.data.joint("spin").qvel[0] == pytest.approx(1.5, rel=1e-3)
    assert sim.data.joint("lift").qpos[0] == pytest.approx(1.0, abs=1e-9)
    last = states[-1]
    assert last.name == ["spin", "lift"]
    assert last.position[0] == pytest.approx(
        sim.data.joint("spin").qpos[0], abs=0.05
    )  # <= 1 period old
    assert last.position[0] > 2.5  # about 1.5 rad/s for 2 s, minus the start
