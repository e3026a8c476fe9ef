"""Sensors from <gazebo reference=...><sensor>: IMU, contact (bumper), sonar, unknown types."""

from __future__ import annotations

import math

import pytest

from robomodel.description.urdf.reader import read_urdf
from robomodel.runtime import Context, ManualClock
from robomodel.runtime.msg.types.sensor_msgs import Imu, LaserScan
from robomodel.sim import Placement, Simulation, parse_world
from robomodel.sim.bus import SimBridge
from robomodel.sim.sensors.msgs import ContactsState, range_type

BOX = """<robot name="box">
  <link name="base">
    <inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision>
  </link>
  <gazebo reference="base">
    <sensor type="imu" name="imu">
      <update_rate>100</update_rate>
      <plugin name="imu_plugin" filename="libgazebo_ros_imu_sensor.so">
        <ros><remapping>~/out:=imu/data</remapping></ros>
      </plugin>
    </sensor>
    <sensor type="contact" name="bumper">
      <update_rate>50</update_rate>
      <contact><collision>base_collision</collision></contact>
      <plugin name="bumper" filename="libgazebo_ros_bumper.so"><ros><remapping>~/out:=bumper</remapping></ros></plugin>
    </sensor>
    <sensor type="sonar" name="sonar">
      <pose>0.1 0 0 0 0 0</pose>
      <update_rate>10</update_rate>
      <sonar><min>0.02</min><max>3</max><radius>0.2</radius></sonar>
    </sensor>
    <sensor type="altimeter" name="alt"/>
  </gazebo>
</robot>"""

WORLD = """<sdf version="1.6"><world name="w">
  <include><uri>model://ground_plane</uri></include>
  <model name="block"><static>true</static><pose>1.6 0 0.5 0 0 0</pose>
    <link name="l"><collision name="c"><geometry><box><size>0.2 1 1</size></box></geometry></collision></link>
  </model>
</world></sdf>"""


def test_imu_contact_and_sonar_publish_and_unknown_types_are_skipped() -> None:
    with pytest.warns(UserWarning, match=r"sensor 'alt' has type 'altimeter'.*skipped"):
        sim = Simulation(parse_world(WORLD))
        sim.add_robot(
            read_urdf(BOX.encode(), path="box.urdf").robot,
            placement=Placement(xyz_m=(0.0, 0.0, 0.1)),
        )
    context = Context(clock=ManualClock())
    SimBridge(sim, context)
    node = context.create_node("test")
    got: dict[str, list[object]] = {"imu": [], "bumper": [], "sonar": []}
    node.create_subscription(Imu, "/imu/data", got["imu"].append)
    node.create_subscription(ContactsState, "/bumper", got["bumper"].append)
    node.create_subscription(range_type(), "/sonar", got["sonar"].append)
    sim.step(1000)
    assert len(got["imu"]) == pytest.approx(100, abs=1)
    imu = got["imu"][-1]
    assert isinstance(imu, Imu)
    assert imu.linear_acceleration.z == pytest.approx(9.81, abs=0.05)  # at rest: +g up
    assert abs(imu.angular_velocity.x) < 1e-3 and imu.orientation.w == pytest.approx(1.0)
    bumper = got["bumper"][-1]
    assert isinstance(bumper, ContactsState) and bumper.states
    assert {"ground_plane", "base_collision"} <= {
        bumper.states[0].collision1_name,
        bumper.states[0].collision2_name,
    }
    total = sum(s.total_wrench_force.z for s in bumper.states)  # type: ignore[attr-defined]
    assert abs(total) == pytest.approx(9.81, rel=0.05)  # the box's weight
    sonar = got["sonar"][-1]
    assert isinstance(sonar, range_type())
    assert sonar.range == pytest.approx(1.5 - 0.1, abs=0.01)  # block face at 1.5 m, sonar at 0.1
    assert sonar.field_of_view == pytest.approx(2 * math.atan2(0.2, 3.0))


def test_lidar_noise_and_range_limits() -> None:
    text = BOX.replace(
        '<sensor type="altimeter" name="alt"/>',
        """<sensor type="gpu_ray" name="laser"><update_rate>0</update_rate>
      <ray><scan><horizontal><samples>5</samples><min_angle>-0.1</min_angle><max_angle>0.1</max_angle></horizontal></scan>
        <range><min>0.05</min><max>1.0</max></range>
        <noise><type>gaussian</type><mean>0</mean><stddev>0.01</stddev></noise></ray>
      <plugin name="p" filename="libgazebo_ros_ray_sensor.so"><ros><remapping>~/out:=far_scan</remapping></ros>
        <output_type>sensor_msgs/LaserScan</output_type></plugin></sensor>""",
    )
    sim = Simulation(parse_world(WORLD))
    sim.add_robot(read_urdf(text.encode()).robot, placement=Placement(xyz_m=(0.0, 0.0, 0.1)))
    context = Context(clock=ManualClock())
    SimBridge(sim, context)
    scans: list[LaserScan] = []
    context.create_node("t").create_subscription(LaserScan, "/far_scan", scans.append)
    sim.step(10)
    context.advance(0.0)  # deliver what was published since the last bus tick
    assert len(scans) == 10  # update_rate 0: every step
    assert all(r == math.inf for r in scans[-1].ranges)  # the block is beyond range.max
    sim.teleport((0.8, 0.0, 0.1))
    sim.step(1)
    context.advance(0.0)
    ranges = scans[-1].ranges
    assert ranges[2] == pytest.approx(0.7, abs=0.04) and ranges[2] != pytest.approx(0.7, abs=1e-9)
