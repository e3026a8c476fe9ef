"""Model building from the URDF model: frames, inertia, joints, friction, collisions, mimic."""

from __future__ import annotations

import mujoco
import numpy as np
import pytest

from robomodel.description.urdf.reader import read_urdf
from robomodel.loading import load
from robomodel.sim import Placement, Simulation, SimulationError

from .conftest import RRBOT, SIMPLEBOT, UR5


def _robot(text: str):  # type: ignore[no-untyped-def]
    return read_urdf(text.encode(), path="bad.urdf").robot


def _urdf(inertia: str, mass: str = "1") -> str:
    return f"""<robot name="r">
  <link name="base"><inertial><mass value="1"/>
    <inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="arm">
    <inertial><mass value="{mass}"/>
      <inertia {inertia}/></inertial></link>
  <joint name="j" type="continuous"><parent link="base"/><child link="arm"/></joint>
</robot>"""


def test_every_urdf_frame_is_a_body_and_fk_matches_our_kinematics() -> None:
    from robomodel.kinematics import Kinematics

    robot = load(str(UR5))
    sim = Simulation()
    sim.add_robot(robot)
    q = np.array([0.3, -1.0, 1.2, -0.4, 0.9, 0.2])
    for name, value in zip(sim.robot().joints, q, strict=True):
        sim.data.joint(name).qpos = value
    mujoco.mj_kinematics(sim.model, sim.data)
    kin = Kinematics(robot)
    names = [sim.model.body(i).name for i in range(sim.model.nbody)]
    assert "ee_link" in names and "world_link" in names  # fixed-joint frames kept
    qk = kin.q_from_dict(dict(zip(sim.robot().joints, q, strict=True)))
    for link in ("ee_link", "wrist_2_link", "forearm_link"):
        T = kin.fk_link(qk, link)
        np.testing.assert_allclose(sim.data.body(link).xpos, T[:3, 3], atol=1e-9)
        np.testing.assert_allclose(sim.data.body(link).xmat.reshape(3, 3), T[:3, :3], atol=1e-9)


def test_full_inertia_tensor_is_reconstructed() -> None:
    text = _urdf('ixx="0.02" iyy="0.03" izz="0.04" ixy="0.001" ixz="-0.002" iyz="0.0005"', "2")
    sim = Simulation()
    sim.add_robot(_robot(text))
    m = sim.model
    bid = m.body("arm").id
    R = np.zeros(9)
    mujoco.mju_quat2Mat(R, m.body_iquat[bid])
    R = R.reshape(3, 3)
    tensor = R @ np.diag(m.body_inertia[bid]) @ R.T
    expected = [[0.02, 0.001, -0.002], [0.001, 0.03, 0.0005], [-0.002, 0.0005, 0.04]]
    np.testing.assert_allclose(tensor, expected, atol=1e-12)
    assert m.body_mass[bid] == 2.0


@pytest.mark.parametrize(
    ("inertia", "mass", "words"),
    [
        ('ixx="0" iyy="0" izz="0" ixy="0" ixz="0" iyz="0"', "1", "not positive definite"),
        ('ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"', "0", "mass 0.0"),
        ('ixx="0.01" iyy="0.01" izz="0.1" ixy="0" ixz="0" iyz="0"', "1", "triangle inequality"),
        ('ixx="0.1" iyy="0.1" izz="0.1" ixy="0.5" ixz="0" iyz="0"', "1", "not positive definite"),
    ],
)
def test_wrong_inertia_is_refused_with_link_and_line(inertia: str, mass: str, words: str) -> None:
    sim = Simulation()
    with pytest.raises(SimulationError) as info:
        sim.add_robot(_robot(_urdf(inertia, mass)))
    message = str(info.value)
    assert words in message and "'arm'" in message
    assert message.startswith("bad.urdf:5")  # the <inertial> line
    assert info.value.name == "arm"


def test_massless_fixed_frames_and_world_links_are_fine() -> None:
    sim = Simulation()
    sim.add_robot(load(str(RRBOT)))
    sim.step(10)
    assert np.isfinite(sim.data.qpos).all()


def test_floating_base_gets_a_free_joint_and_falls_onto_the_ground() -> None:
    sim = Simulation()
    sim.add_robot(load(str(SIMPLEBOT)), placement=Placement(xyz_m=(0.0, 0.0, 0.3)))
    assert sim.model.jnt_type[0] == mujoco.mjtJoint.mjJNT_FREE
    sim.step(1000)
    z = sim.data.body("base_link").xpos[2]
    assert z == pytest.approx(0.075, abs=0.005)  # resting on its wheels (radius 0.075 m)


def test_gazebo_friction_min_rule_and_no_self_collision() -> None:
    sim = Simulation()
    sim.add_robot(load(str(SIMPLEBOT)))
    m = sim.model
    caster = m.geom("caster_collision")
    ground = m.geom("ground_plane")
    assert caster.friction[0] == 0.0 and ground.friction[0] == 100.0
    assert caster.priority[0] > ground.priority[0]  # the lower mu wins, as min(mu1, mu2)
    base, wheel = m.geom("base_link_collision"), m.geom("left_wheel_collision")
    assert not (base.contype[0] & wheel.conaffinity[0]) and not (
        wheel.contype[0] & base.conaffinity[0]
    )
    assert base.contype[0] & ground.conaffinity[0]


def test_limits_damping_and_effort_limit_in_radians() -> None:
    sim = Simulation()
    sim.add_robot(load(str(UR5)))
    joint = sim.model.joint("shoulder_pan_joint")
    robot_joint = load(str(UR5)).joint("shoulder_pan_joint")
    assert robot_joint.limit is not None
    np.testing.assert_allclose(
        joint.range, [robot_joint.limit.lower, robot_joint.limit.upper], rtol=1e-12
    )


def test_mimic_joint_is_an_equality_constraint() -> None:
    text = """<robot name="g">
  <link name="base"/>
  <link name="a"><inertial><mass value="0.1"/><inertia ixx="1e-4" iyy="1e-4" izz="1e-4" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="b"><inertial><mass value="0.1"/><inertia ixx="1e-4" iyy="1e-4" izz="1e-4" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="ja" type="revolute"><parent link="base"/><child link="a"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="10" velocity="1"/></joint>
  <joint name="jb" type="revolute"><parent link="base"/><child link="b"/><axis xyz="0 0 1"/>
    <limit lower="-2" upper="2" effort="10" velocity="1"/><mimic joint="ja" multiplier="-2" offset="0.1"/></joint>
  <gazebo><static>true</static></gazebo>
</robot>"""
    sim = Simulation()
    sim.add_robot(_robot(text))
    sim.data.qfrc_applied[0] = 1e-3
    sim.step(500)
    qa, qb = sim.data.joint("ja").qpos[0], sim.data.joint("jb").qpos[0]
    assert abs(qa) > 0.05
    assert qb == pytest.approx(0.1 - 2 * qa, abs=2e-3)


def test_missing_mesh_is_refused_with_the_collision_line() -> None:
    text = """<robot name="m">
  <link name="base">
    <collision><geometry><mesh filename="does/not/exist.stl"/></geometry></collision>
  </link>
  <gazebo><static>true</static></gazebo>
</robot>"""
    with pytest.raises(
        SimulationError, match=r"bad.urdf:3:\d+: mesh file 'does/not/exist.stl' not found"
    ):
        Simulation().add_robot(_robot(text))


def test_dae_mesh_collision_loads_through_trimesh(tmp_path) -> None:  # type: ignore[no-untyped-def]
    trimesh = pytest.importorskip("trimesh")
    box = trimesh.creation.box(extents=(0.2, 0.2, 0.2))
    path = tmp_path / "box.dae"
    box.export(path)
    text = f"""<robot name="m"><link name="base">
    <inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><mesh filename="{path}" scale="2 2 2"/></geometry></collision>
  </link></robot>"""
    sim = Simulation()
    sim.add_robot(_robot(text), placement=Placement(xyz_m=(0, 0, 1)))
    sim.step(1500)
    assert sim.data.body("base").xpos[2] == pytest.approx(0.2, abs=0.01)  # half of 0.4 m


def test_visuals_are_optional_collision_free_and_coloured_by_gazebo_materials() -> None:
    from robomodel.sim.build.gazebo import GAZEBO_MATERIALS

    assert Simulation().model.ngeom == 1  # the ground only
    plain = Simulation()
    plain.add_robot(load(str(RRBOT)))
    sim = Simulation(include_visuals=True)
    sim.add_robot(load(str(RRBOT)))
    m = sim.model
    visuals = [g for g in range(m.ngeom) if m.geom_group[g] == 1]
    assert len(visuals) == m.ngeom - plain.model.ngeom > 0
    assert all(m.geom_contype[g] == 0 and m.geom_conaffinity[g] == 0 for g in visuals)
    link1 = m.body("link1").id
    colours = [m.geom_rgba[g] for g in visuals if m.geom_bodyid[g] == link1]
    assert colours
    for rgba in colours:  # <gazebo reference="link1"><material>Gazebo/Orange
        np.testing.assert_allclose(rgba, GAZEBO_MATERIALS["Gazebo/Orange"], rtol=1e-6)


ARMATURE = """<robot name="r" xmlns:drake="http://drake.mit.edu">
  <link name="world"/>
  <link name="arm"><inertial><origin xyz="0 0 0"/><mass value="1"/>
    <inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="j" type="continuous"><parent link="world"/><child link="arm"/>
    <axis xyz="0 0 1"/></joint>
  <transmission name="t"><type>transmission_interface/SimpleTransmission</type>
    <joint name="j"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
    <actuator name="m"><mechanicalReduction>50</mechanicalReduction>
      <drake:rotor_inertia value="{rotor}"/>{gear}</actuator>
  </transmission>
  <gazebo reference="j"><springStiffness>2.0</springStiffness><springReference>0.3</springReference></gazebo>
</robot>"""


def test_armature_from_drake_rotor_inertia_and_springs_from_gazebo_joint_tags() -> None:
    from robomodel.description.urdf.writer import urdf_to_string

    robot = _robot(ARMATURE.format(rotor="4e-5", gear='\n      <drake:gear_ratio value="100"/>'))
    assert read_urdf(urdf_to_string(robot).encode()).robot == robot  # kept on a round trip
    sim = Simulation()
    sim.add_robot(robot)
    joint = sim.model.joint("j")
    assert joint.armature[0] == pytest.approx(4e-5 * 100**2)  # reflected: I_rotor N^2 = 0.4
    assert joint.stiffness[0] == 2.0
    assert sim.model.qpos_spring[joint.qposadr[0]] == 0.3  # springref
    # undamped spring from q = 0 about 0.3: the first maximum (0.6) after half a period,
    # pi sqrt(I / k) with I = 0.01 (link) + 0.4 (armature) = 1.422 s (0.222 s without armature)
    trace = []
    for _ in range(2500):
        sim.step(1)
        trace.append(float(sim.data.joint("j").qpos[0]))
    assert max(trace) == pytest.approx(0.6, abs=1e-3)
    assert (1 + int(np.argmax(trace))) * 1e-3 == pytest.approx(np.pi * np.sqrt(0.41 / 2), abs=2e-3)
    # without drake:gear_ratio the actuator's mechanicalReduction is the gear ratio
    sim = Simulation()
    sim.add_robot(_robot(ARMATURE.format(rotor="4e-5", gear="")))
    assert sim.model.joint("j").armature[0] == pytest.approx(4e-5 * 50**2)


def test_bad_rotor_inertia_is_refused_with_its_line() -> None:
    sim = Simulation()
    with pytest.raises(SimulationError, match=r"bad\.urdf:10:7: <drake:rotor_inertia.*>= 0"):
        sim.add_robot(_robot(ARMATURE.format(rotor="-1", gear="")))
