"""FK interface: shapes, subsets, read-only outputs, bad input, joint types, mimic chains."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pinocchio
import pytest

from robomodel.description import TreeError, UnknownNameError, read_urdf
from robomodel.kinematics import (
    ConfigurationError,
    Kinematics,
    MimicCycleError,
    ZeroAxisError,
)
from tests.kinematics._pin import pin_link_poses


def _robot(joints: str, links: str = "") -> Kinematics:
    names = {"base", "a", "b", "c"}
    text = "<robot name='r'>" + "".join(f"<link name='{n}'/>" for n in sorted(names)) + links
    return Kinematics(read_urdf(text + joints + "</robot>").robot)


CHAIN = """
<joint name='j1' type='revolute'><parent link='base'/><child link='a'/>
  <origin xyz='0 0 1' rpy='0.1 0.2 0.3'/><axis xyz='0 2 0'/><limit lower='-1' upper='1' effort='1' velocity='1'/></joint>
<joint name='j2' type='prismatic'><parent link='a'/><child link='b'/>
  <origin xyz='1 0 0'/><axis xyz='1 1 0'/><limit lower='0' upper='0.5' effort='1' velocity='1'/></joint>
<joint name='j3' type='continuous'><parent link='b'/><child link='c'/><axis xyz='0 0 -1'/></joint>
"""


def test_shapes_subsets_and_read_only() -> None:
    kin = _robot(CHAIN)
    assert kin.joint_names == ("j1", "j2", "j3")
    assert kin.link_names == ("base", "a", "b", "c")
    np.testing.assert_array_equal(kin.lower, [-1, 0, -math.inf])
    q = np.array([0.3, 0.2, 1.0])
    Ts = kin.fk(q)
    assert Ts.shape == (4, 4, 4) and Ts.dtype == np.float64
    with pytest.raises(ValueError):
        Ts[0, 0, 0] = 2.0
    batch = kin.fk(np.tile(q, (2, 3, 1)))
    assert batch.shape == (2, 3, 4, 4, 4)
    np.testing.assert_allclose(batch[1, 2], Ts, atol=1e-15)
    sub = kin.fk(q, links=["c", "a"])
    np.testing.assert_array_equal(sub, Ts[[3, 1]])
    np.testing.assert_allclose(kin.fk(q[None], links=["c"])[0, 0], Ts[3], atol=1e-15)
    np.testing.assert_allclose(kin.fk_link(q, "b"), Ts[2])


def test_joint_semantics_by_hand() -> None:
    kin = _robot(CHAIN)
    Ts = kin.fk([0.0, 0.5, 0.0])
    # Prismatic moves 0.5 along the normalised axis (1, 1, 0)/sqrt(2), in a's frame.
    p_in_a = np.linalg.inv(Ts[1]) @ Ts[2][:, 3]
    np.testing.assert_allclose(
        p_in_a[:3], [1 + 0.5 / math.sqrt(2), 0.5 / math.sqrt(2), 0], atol=1e-12
    )
    # Continuous about -z: +0.5 rad turns clockwise about z.
    T = kin.fk([0.0, 0.0, 0.5])
    R_b_c = (np.linalg.inv(T[2]) @ T[3])[:3, :3]
    np.testing.assert_allclose(R_b_c[0, 1], math.sin(0.5), atol=1e-12)


def test_bad_input_messages() -> None:
    kin = _robot(CHAIN)
    with pytest.raises(ConfigurationError, match=r"expected \(3,\) or \(\.\.\., 3\)"):
        kin.fk([0.0, 0.0])
    with pytest.raises(ConfigurationError, match="joint 'j2'"):
        kin.fk([0.0, math.nan, 0.0])
    with pytest.raises(ConfigurationError, match=r"'j3'.*batch index"):
        kin.fk([[0.0, 0.0, 0.0], [0.0, 0.0, math.inf]])
    with pytest.raises(UnknownNameError, match="did you mean 'a'"):
        kin.fk([0, 0, 0], links=["aa"])
    # Outside the limits: accepted unless asked.
    kin.fk([5.0, 0.0, 0.0])
    with pytest.raises(ConfigurationError, match=r"'j1' = 5.0 is outside its limits \[-1.0, 1.0\]"):
        kin.fk([5.0, 0.0, 0.0], check_limits=True)
    assert kin.within_limits([[0, 0, 9], [2, 0, 0]]).tolist() == [True, False]


def test_zero_axis_and_tree_errors() -> None:
    with pytest.raises(ZeroAxisError, match="joint 'j'"):
        _robot(
            "<joint name='j' type='continuous'><parent link='base'/><child link='a'/><axis xyz='0 0 0'/></joint>"
            "<joint name='k' type='fixed'><parent link='a'/><child link='b'/></joint>"
            "<joint name='l' type='fixed'><parent link='b'/><child link='c'/></joint>"
        )
    # A robot that is not a tree never reaches Kinematics through the parser; built directly:
    robot = read_urdf(
        CHAIN.join(
            [
                "<robot name='r'><link name='base'/><link name='a'/><link name='b'/><link name='c'/>",
                "</robot>",
            ]
        )
    ).robot
    broken = dataclasses.replace(robot, joints=robot.joints[:1])
    with pytest.raises(TreeError, match="Two root links"):
        Kinematics(broken)


def _mimic_robot(m23: str, m34: str) -> str:
    return f"""<robot name='m'><link name='l1'/><link name='l2'/><link name='l3'/><link name='l4'/>
<joint name='j12' type='revolute'><parent link='l1'/><child link='l2'/><axis xyz='0 0 1'/><limit lower='-1' upper='1' effort='1' velocity='1'/></joint>
<joint name='j23' type='revolute'><parent link='l2'/><child link='l3'/><axis xyz='0 0 1'/><limit lower='-1' upper='1' effort='1' velocity='1'/>{m23}</joint>
<joint name='j34' type='revolute'><parent link='l3'/><child link='l4'/><axis xyz='0 0 1'/><limit lower='-1' upper='1' effort='1' velocity='1'/>{m34}</joint>
</robot>"""


def test_mimic_chain_resolved_like_joint_state_publisher() -> None:
    # joint_state_publisher's test_mimic_chain: j23 = j12 + 0.1, j34 = -j23.
    text = _mimic_robot("<mimic joint='j12' offset='0.1'/>", "<mimic joint='j23' multiplier='-1'/>")
    kin = Kinematics(read_urdf(text).robot)
    assert kin.joint_names == ("j12",)
    assert kin.mimic["j34"] == ("j12", -1.0, -0.1)
    Ts = kin.fk([0.0])
    R_2_3 = (np.linalg.inv(Ts[1]) @ Ts[2])[:3, :3]
    np.testing.assert_allclose(R_2_3[1, 0], math.sin(0.1), atol=1e-15)
    np.testing.assert_allclose(Ts[3][:3, :3], np.eye(3), atol=1e-15)


def test_mimic_cycle_is_an_error_listing_the_cycle() -> None:
    text = _mimic_robot("<mimic joint='j34'/>", "<mimic joint='j23'/>")
    with pytest.raises(MimicCycleError, match="j23 -> j34 -> j23"):
        Kinematics(read_urdf(text).robot)


FLOATING_PLANAR = """<robot name='fp'><link name='world'/><link name='body'/><link name='cart'/><link name='arm'/>
<joint name='free' type='floating'><parent link='world'/><child link='body'/><origin xyz='0.1 0.2 0.3' rpy='0.3 0.2 0.1'/></joint>
<joint name='slide' type='planar'><parent link='body'/><child link='cart'/><origin xyz='0 0 0.5' rpy='0 0.4 0'/><axis xyz='0 0 1'/></joint>
<joint name='turn' type='continuous'><parent link='cart'/><child link='arm'/><origin xyz='0.2 0 0'/><axis xyz='1 0 0'/></joint>
</robot>"""


def test_floating_and_planar_match_pinocchio(tmp_path: object) -> None:
    kin = Kinematics(read_urdf(FLOATING_PLANAR).robot)
    assert kin.n_q == 7 + 3 + 1
    assert kin.q_names[:3] == ("free[0]", "free[1]", "free[2]")
    np.testing.assert_array_equal(kin.neutral()[:7], [0, 0, 0, 0, 0, 0, 1])
    model = pinocchio.buildModelFromXML(FLOATING_PLANAR)
    rng = np.random.default_rng(0)
    for _ in range(5):
        q = rng.uniform(-2, 2, kin.n_q)
        q_unit = q.copy()
        q_unit[3:7] /= np.linalg.norm(q_unit[3:7])
        expected = pin_link_poses(kin, model, q_unit)  # pinocchio needs a unit quaternion
        np.testing.assert_allclose(kin.fk(q), expected, atol=1e-10)  # we normalise it
        np.testing.assert_allclose(kin.fk(q[None])[0], expected, atol=1e-10)


def test_planar_basis_for_a_tilted_axis() -> None:
    text = FLOATING_PLANAR.replace("<axis xyz='0 0 1'/>", "<axis xyz='1 0 0'/>")
    kin = Kinematics(read_urdf(text).robot)
    q = kin.neutral()
    q[7:10] = [0.3, 0.4, 0.5]
    Ts = kin.fk(q)
    T_body_cart = np.linalg.inv(Ts[1]) @ Ts[2]
    origin = read_urdf(text).robot.joint("slide").origin.matrix()
    local = np.linalg.inv(origin) @ T_body_cart
    # Plane normal x: the smallest rotation taking z to x maps x -> -z and y -> y.
    np.testing.assert_allclose(
        local[:3, 3], 0.3 * np.array([0, 0, -1]) + 0.4 * np.array([0, 1, 0]), atol=1e-12
    )
    np.testing.assert_allclose(
        local[1:3, 1:3],
        [[math.cos(0.5), -math.sin(0.5)], [math.sin(0.5), math.cos(0.5)]],
        atol=1e-12,
    )
