"""The URDF parser: every element and attribute, versions, numbers and API forms."""

from __future__ import annotations

import math
import warnings
from pathlib import Path

import pytest

from robomodel.description import (
    Box,
    Capsule,
    Cylinder,
    JointType,
    Mesh,
    Sphere,
    TransmissionStyle,
    URDFWarning,
    parse_urdf,
    read_urdf,
)
from robomodel.errors import InputError

FULL = """<?xml version="1.0"?>
<robot name="full" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <material name="red"><color rgba="1 0 0 1"/></material>
  <material name="tex"><texture filename="package://p/t.png"/></material>
  <link name="base">
    <inertial>
      <origin xyz="0.1 0 0" rpy="0 0 0.5"/>
      <mass value="2.5"/>
      <inertia ixx="1" ixy="0.1" ixz="0.2" iyy="2" iyz="0.3" izz="2.5"/>
    </inertial>
    <visual name="v1">
      <origin xyz="1 2 3" rpy="0.1 0.2 0.3"/>
      <geometry><box size="1 2 3"/></geometry>
      <material name="red"/>
    </visual>
    <visual>
      <geometry><mesh filename="package://p/m.dae" scale="2 2 2"/></geometry>
      <material name="green"><color rgba="0 1 0 0.5"/></material>
    </visual>
    <collision name="c1"><geometry><cylinder radius="0.5" length="2"/></geometry></collision>
    <collision><geometry><sphere radius="0.25"/></geometry></collision>
    <sensor_extension foo="bar"><child/></sensor_extension>
  </link>
  <link name="arm"/>
  <link name="slider"/>
  <link name="wheel"/>
  <link name="free"/>
  <link name="plane"/>
  <joint name="j_rev" type="revolute">
    <origin xyz="0 0 1" rpy="0 1.5707963267948966 0"/>
    <parent link="base"/>
    <child link="arm"/>
    <axis xyz="0 1 0"/>
    <limit lower="-1" upper="1" effort="10" velocity="2"/>
    <dynamics damping="0.5" friction="0.1"/>
    <safety_controller soft_lower_limit="-0.9" soft_upper_limit="0.9" k_position="10" k_velocity="5"/>
    <calibration rising="0.1" falling="0.2"/>
  </joint>
  <joint name="j_pri" type="prismatic">
    <parent link="base"/>
    <child link="slider"/>
    <axis xyz="0 0 1"/>
    <limit lower="0" upper="0.5" effort="100" velocity="0.1"/>
    <mimic joint="j_rev" multiplier="0.5" offset="0.1"/>
  </joint>
  <joint name="j_con" type="continuous">
    <parent link="arm"/>
    <child link="wheel"/>
  </joint>
  <joint name="j_free" type="floating"><parent link="base"/><child link="free"/></joint>
  <joint name="j_plane" type="planar"><parent link="base"/><child link="plane"/><axis xyz="0 0 1"/></joint>
  <transmission name="t1">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="j_rev"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
    <actuator name="m1"><hardwareInterface>EffortJointInterface</hardwareInterface><mechanicalReduction>50</mechanicalReduction></actuator>
  </transmission>
  <transmission name="t_pr2" type="pr2_mechanism_model/SimpleTransmission">
    <actuator name="m2"/><joint name="j_pri"/><mechanicalReduction>3</mechanicalReduction>
  </transmission>
  <gazebo reference="arm"><mu1>0.2</mu1><material>Gazebo/Red</material></gazebo>
  <gazebo><plugin name="gazebo_ros_control" filename="libgazebo_ros_control.so"/></gazebo>
  <ros2_control name="Sys" type="system" is_async="true">
    <hardware>
      <plugin>mock_components/GenericSystem</plugin>
      <param name="calculate_dynamics">true</param>
    </hardware>
    <joint name="j_rev">
      <command_interface name="position"><param name="min">-1</param><param name="max">1</param></command_interface>
      <state_interface name="position"><param name="initial_value">0.5</param></state_interface>
      <state_interface name="velocity"/>
    </joint>
    <sensor name="ft"><state_interface name="force.x"/><param name="frame_id">arm</param></sensor>
    <gpio name="io"><command_interface name="vacuum"/><state_interface name="vacuum" data_type="double" size="1"/></gpio>
    <transmission name="t2">
      <plugin>transmission_interface/SimpleTransmission</plugin>
      <actuator name="a1" role="actuator1"/>
      <joint name="j_rev" role="joint1"><mechanical_reduction>325.9</mechanical_reduction><offset>0.1</offset></joint>
    </transmission>
  </ros2_control>
  <custom_top_level attr="1"/>
</robot>
"""


@pytest.fixture(scope="module")
def full():  # type: ignore[no-untyped-def]
    return read_urdf(FULL, path="full.urdf")


def test_links_and_geometry(full) -> None:  # type: ignore[no-untyped-def]
    robot = full.robot
    assert robot.name == "full" and robot.link_names[0] == "base"
    base = robot.link("base")
    assert base.inertial is not None
    assert base.inertial.mass_kg == 2.5
    assert base.inertial.inertia.iyz == 0.3
    assert base.inertial.origin.rpy_rad == (0.0, 0.0, 0.5)
    assert [v.name for v in base.visuals] == ["v1", None]
    assert base.visuals[0].geometry == Box((1.0, 2.0, 3.0))
    assert base.visuals[0].material is not None and base.visuals[0].material.is_reference
    assert base.visuals[1].geometry == Mesh("package://p/m.dae", (2.0, 2.0, 2.0))
    assert base.visuals[1].material is not None and base.visuals[1].material.rgba == (0, 1, 0, 0.5)
    assert base.collisions[0].geometry == Cylinder(0.5, 2.0)
    assert base.collisions[1].geometry == Sphere(0.25)
    assert base.extra[0].tag == "sensor_extension" and 'foo="bar"' in base.extra[0].xml
    assert robot.material("tex").texture == "package://p/t.png"


def test_joints(full) -> None:  # type: ignore[no-untyped-def]
    robot = full.robot
    rev = robot.joint("j_rev")
    assert rev.type is JointType.REVOLUTE
    assert rev.axis == (0.0, 1.0, 0.0)
    assert rev.limit is not None and (rev.limit.lower, rev.limit.upper) == (-1.0, 1.0)
    assert rev.dynamics is not None and rev.dynamics.friction == 0.1
    assert rev.safety_controller is not None and rev.safety_controller.k_velocity == 5
    assert rev.calibration is not None and rev.calibration.falling == 0.2
    pri = robot.joint("j_pri")
    assert pri.mimic is not None and pri.mimic.multiplier == 0.5 and pri.mimic.offset == 0.1
    con = robot.joint("j_con")
    assert con.axis == (1.0, 0.0, 0.0) and con.limit is None  # urdfdom's default axis
    assert robot.joint("j_free").type is JointType.FLOATING
    assert robot.joint("j_plane").type is JointType.PLANAR


def test_extensions(full) -> None:  # type: ignore[no-untyped-def]
    robot = full.robot
    t1, pr2 = robot.transmissions
    assert (
        t1.style is TransmissionStyle.ROS1
        and t1.type == "transmission_interface/SimpleTransmission"
    )
    assert t1.joints[0].hardware_interfaces == ("hardware_interface/EffortJointInterface",)
    assert t1.actuators[0].mechanical_reduction == 50
    assert pr2.style is TransmissionStyle.ROS1_TYPE_ATTRIBUTE and pr2.mechanical_reduction == 3
    assert [g.reference for g in robot.gazebo] == ["arm", None]
    assert "<mu1>0.2</mu1>" in robot.gazebo[0].xml
    (block,) = robot.ros2_control
    assert block.hardware_plugin == "mock_components/GenericSystem"
    assert block.hardware_params == (("calculate_dynamics", "true"),)
    assert block.attributes == (("is_async", "true"),)
    joint = block.joints[0]
    assert joint.command_interfaces[0].min == "-1" and joint.command_interfaces[0].max == "1"
    assert joint.state_interfaces[0].initial_value == "0.5"
    assert block.sensors[0].params == (("frame_id", "arm"),)
    assert block.gpios[0].state_interfaces[0].data_type == "double"
    assert block.gpios[0].state_interfaces[0].size == 1
    (t2,) = block.transmissions
    assert t2.style is TransmissionStyle.ROS2
    assert t2.joints[0].role == "joint1" and t2.joints[0].mechanical_reduction == 325.9
    assert t2.joints[0].offset == 0.1
    assert robot.extra[0].tag == "custom_top_level"


def test_children_in_joint_name_order() -> None:
    xml = """<robot name="order"><link name="base"/>
      <link name="first_in_file"/><link name="second_in_file"/><link name="third_in_file"/>
      <joint name="z_joint" type="fixed"><parent link="base"/><child link="first_in_file"/></joint>
      <joint name="a_joint" type="fixed"><parent link="base"/><child link="second_in_file"/></joint>
      <joint name="M_joint" type="fixed"><parent link="base"/><child link="third_in_file"/></joint>
    </robot>"""
    tree = read_urdf(xml).robot.tree()
    assert tree.root == "base"
    assert tree.children("base") == ("third_in_file", "second_in_file", "first_in_file")
    assert tree.parent("first_in_file") == "base"


def test_path_string_and_bytes_give_equal_models(tmp_path: Path) -> None:
    path = tmp_path / "full.urdf"
    path.write_text(FULL)
    from_path = read_urdf(path).robot
    assert read_urdf(str(path)).robot == from_path
    assert read_urdf(FULL).robot == from_path
    assert read_urdf(FULL.encode()).robot == from_path


def test_versions() -> None:
    body = '<link name="a"/><link name="b"/><joint name="j" type="revolute"><parent link="a"/><child link="b"/>'
    v11 = f'<robot name="r" version="1.1">{body}<origin quat_xyzw="0 0 0 2"/><limit lower="0" upper="1" effort="1" velocity="1"/></joint></robot>'
    joint = read_urdf(v11).robot.joint("j")
    assert joint.origin.quat_xyzw == (0.0, 0.0, 0.0, 2.0)
    assert joint.origin.quaternion_xyzw() == (0.0, 0.0, 0.0, 1.0)
    v12 = f'<robot name="r" version="1.2">{body}<limit lower="0" upper="1" acceleration="2" jerk="3"/></joint></robot>'
    limit = read_urdf(v12).robot.joint("j").limit
    assert (
        limit is not None and limit.acceleration == 2 and limit.jerk == 3 and limit.effort is None
    )
    assert math.isinf(limit.effort_or_inf)
    # quat_xyzw in a 1.0 file is ignored with urdfdom 6's warning, rpy is used.
    v10 = f'<robot name="r">{body}<origin quat_xyzw="0 0 1 0"/><limit lower="0" upper="1" effort="1" velocity="1"/></joint></robot>'
    result = read_urdf(v10)
    assert result.robot.joint("j").origin.quat_xyzw is None
    assert any("quat_xyzw" in d.message for d in result.diagnostics)
    capsule = '<robot name="r" version="1.1"><link name="a"><visual><geometry><capsule radius="1" length="2"/></geometry></visual></link></robot>'
    assert read_urdf(capsule).robot.link("a").visuals[0].geometry == Capsule(1.0, 2.0)
    for good in ("1.0", " 1.0", "01.00", "1.2"):
        read_urdf(f'<robot name="r" version="{good}"><link name="a"/></robot>')


@pytest.mark.parametrize(
    ("text", "ok"),
    [
        ("1e-3", True),
        (" .5", True),
        ("+1", True),
        ("-0", True),
        ("5.", True),
        ("1E2", True),
        ("nan", False),
        ("inf", False),
        ("-inf", False),
        ("1e400", False),
        ("1_000", False),
        ("1.0 ", False),
        ("0x10", False),
        ("1,5", False),
        ("", False),
        ("one", False),
    ],
)
def test_numbers_follow_strToDouble(text: str, ok: bool) -> None:
    xml = f'<robot name="r"><link name="a"/><link name="b"/><joint name="j" type="revolute"><parent link="a"/><child link="b"/><limit lower="{text}" upper="1" effort="1" velocity="1"/></joint></robot>'
    if ok:
        read_urdf(xml)
    else:
        with pytest.raises(InputError) as info:
            read_urdf(xml, path="n.urdf")
        assert info.value.line == 1 and info.value.column is not None
        assert "lower value" in info.value.message


def test_parse_urdf_emits_warnings() -> None:
    xml = '<robot name="r"><link name="a"><inertial><mass value="-1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link></robot>'
    with pytest.warns(URDFWarning, match="mass"):
        robot = parse_urdf(xml)
    assert robot.link("a").inertial is not None


def test_clean_file_has_no_warnings() -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        parse_urdf('<robot name="r"><link name="a"/></robot>')


def test_error_location_in_multiline_start_tag() -> None:
    xml = '<robot name="r">\n  <link name="a"/>\n  <link name="b"/>\n  <joint\n     name="j"\n     type="revolute">\n    <parent link="a"/><child link="b"/>\n  </joint>\n</robot>'
    with pytest.raises(InputError) as info:
        read_urdf(xml, path="m.urdf")
    assert (info.value.line, info.value.column) == (4, 3)
    assert str(info.value).startswith("m.urdf:4:3: error: Joint [j] is of type REVOLUTE")


def test_unknown_name_lists_valid_names(full) -> None:  # type: ignore[no-untyped-def]
    from robomodel.description import UnknownNameError

    with pytest.raises(UnknownNameError) as info:
        full.robot.link("bse")
    assert "did you mean 'base'" in str(info.value)
    assert "links are: base, arm" in str(info.value)
