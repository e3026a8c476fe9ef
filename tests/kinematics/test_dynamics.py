"""Dynamics against pinocchio on the example-robot-data arms (to 1e-9)."""

from __future__ import annotations

import functools
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from robomodel.kinematics import Kinematics
from robomodel.kinematics.exceptions import ConfigurationError
from tests.conftest import EXAMPLES, example_robot_data_dir

pin = pytest.importorskip("pinocchio")

ARMS = [
    "ur_description/urdf/ur5_robot.urdf",
    "ur_description/urdf/ur10_robot.urdf",
    "z1_description/urdf/z1.urdf",
    "xarm_description/urdf/xarm7.urdf",
    "double_pendulum_description/urdf/double_pendulum.urdf",
    "so_arm_description/urdf/so101.urdf",
]


def _pin(path: Path) -> tuple[object, object]:
    model = pin.buildModelFromUrdf(str(path))
    return model, model.createData()


@pytest.mark.parametrize("relative", ARMS)
def test_dynamics_matches_pinocchio(relative: str) -> None:
    path = example_robot_data_dir() / relative
    kin = Kinematics.load(path)
    dyn = kin.dynamics()
    model, data = _pin(path)
    rng = np.random.default_rng(7)
    for _ in range(5):
        q, v, a = (rng.uniform(-1.5, 1.5, kin.n_q) for _ in range(3))
        np.testing.assert_allclose(dyn.rnea(q, v, a), pin.rnea(model, data, q, v, a), atol=1e-9)
        M = pin.crba(model, data, q)
        M = np.triu(M) + np.triu(M, 1).T
        np.testing.assert_allclose(dyn.mass_matrix(q), M, atol=1e-9)
        np.testing.assert_allclose(
            dyn.gravity(q), pin.computeGeneralizedGravity(model, data, q), atol=1e-9
        )
        np.testing.assert_allclose(
            dyn.nonlinear_effects(q, v), pin.nonLinearEffects(model, data, q, v), atol=1e-9
        )
        np.testing.assert_allclose(
            dyn.coriolis(q, v),
            pin.nonLinearEffects(model, data, q, v) - pin.computeGeneralizedGravity(model, data, q),
            atol=1e-9,
        )
        np.testing.assert_allclose(
            dyn.center_of_mass(q, moving_only=True), pin.centerOfMass(model, data, q), atol=1e-9
        )
        tau = rng.uniform(-5, 5, kin.n_q)
        np.testing.assert_allclose(
            dyn.forward_dynamics(q, v, tau), pin.aba(model, data, q, v, tau), atol=1e-8
        )
    assert dyn.moving_mass_kg() == pytest.approx(pin.computeTotalMass(model), abs=1e-9)


def test_total_mass_counts_the_base_and_shapes_are_checked() -> None:
    kin = Kinematics.load(EXAMPLES / "two_link_arm" / "urdf" / "two_link_arm.urdf")
    dyn = kin.dynamics()
    assert dyn.total_mass_kg > 0
    assert np.all(np.linalg.eigvalsh(dyn.mass_matrix(np.zeros(kin.n_q))) > 0)
    with pytest.raises(ConfigurationError, match="expected"):
        dyn.rnea([0.0], [0.0], [0.0])


def test_single_pendulum_gravity_by_hand() -> None:
    urdf = """<robot name="p"><link name="base"/>
    <link name="bob"><inertial><origin xyz="1 0 0"/><mass value="2"/>
    <inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/></inertial></link>
    <joint name="j" type="continuous"><parent link="base"/><child link="bob"/>
    <axis xyz="0 1 0"/></joint></robot>"""
    kin = Kinematics.load(urdf)
    dyn = kin.dynamics()
    # horizontal arm of 1 m with 2 kg: torque about +y to hold it is -m g l (gravity pulls -z)
    assert dyn.gravity([0.0])[0] == pytest.approx(-2 * 9.81)
    assert dyn.mass_matrix([0.3])[0, 0] == pytest.approx(2.0)


@functools.cache
def _ur5() -> Kinematics:
    return Kinematics.load(example_robot_data_dir() / ARMS[0])


vec6 = st.lists(st.floats(-3.0, 3.0), min_size=6, max_size=6)


@settings(max_examples=40, deadline=None)
@given(vec6, vec6, vec6)
def test_forward_and_inverse_dynamics_round_trip(
    q: list[float], v: list[float], tau: list[float]
) -> None:
    dyn = _ur5().dynamics()
    a = dyn.forward_dynamics(q, v, tau)
    np.testing.assert_allclose(dyn.rnea(q, v, a), tau, atol=1e-8)
    M = dyn.mass_matrix(q)
    np.testing.assert_allclose(M, M.T, atol=1e-12)
    assert np.all(np.linalg.eigvalsh(M) > 0)
    # power balance: d/dt(T + V) = v·tau, i.e. v·(M a + C v + g) = v·tau
    np.testing.assert_allclose(
        float(np.dot(v, M @ a + dyn.nonlinear_effects(q, v))), float(np.dot(v, tau)), atol=1e-7
    )


def _link(name: str, mass: float, com: str, inertia: str = "0.01 0.002 0.0 0.02 0.001 0.03") -> str:
    ixx, ixy, ixz, iyy, iyz, izz = inertia.split()
    return (
        f'<link name="{name}"><inertial><origin xyz="{com}" rpy="0.1 -0.2 0.3"/>'
        f'<mass value="{mass}"/><inertia ixx="{ixx}" ixy="{ixy}" ixz="{ixz}" iyy="{iyy}" '
        f'iyz="{iyz}" izz="{izz}"/></inertial></link>'
    )


def _joint(name: str, kind: str, parent: str, child: str, extra: str = "") -> str:
    return (
        f'<joint name="{name}" type="{kind}"><parent link="{parent}"/><child link="{child}"/>'
        f'<origin xyz="0.1 0.2 0.3" rpy="0.3 0.2 -0.1"/><axis xyz="0.6 0 0.8"/>'
        f'<limit lower="-2" upper="2" effort="1" velocity="1"/>{extra}</joint>'
    )


# Fixed links with mass between and after the moving joints, a prismatic joint, and a base fixed
# to the root: the parts of a model that are not revolute arms.
PRISMATIC_AND_FIXED = (
    '<robot name="mixed"><link name="world"/>'
    + _link("base", 3.0, "0 0 0.1")
    + _link("a", 1.0, "0.2 0 0")
    + _link("bracket", 0.7, "0 0.1 0")
    + _link("slider", 0.5, "0 0 0.15")
    + _link("sensor", 0.2, "0.05 0.05 0")
    + _link("b", 0.8, "0.1 0.1 0")
    + _joint("mount", "fixed", "world", "base")
    + _joint("j1", "revolute", "base", "a")
    + _joint("bolt", "fixed", "a", "bracket")
    + _joint("j2", "prismatic", "bracket", "slider")
    + _joint("cam", "fixed", "slider", "sensor")
    + _joint("j3", "revolute", "sensor", "b")
    + "</robot>"
)


def test_fixed_links_and_a_prismatic_joint_match_pinocchio(tmp_path: Path) -> None:
    path = tmp_path / "mixed.urdf"
    path.write_text(PRISMATIC_AND_FIXED)
    dyn = Kinematics.load(path).dynamics()
    model, data = _pin(path)
    rng = np.random.default_rng(3)
    for _ in range(5):
        q, v, a = (rng.uniform(-1.5, 1.5, 3) for _ in range(3))
        np.testing.assert_allclose(dyn.rnea(q, v, a), pin.rnea(model, data, q, v, a), atol=1e-9)
        M = pin.crba(model, data, q)
        np.testing.assert_allclose(dyn.mass_matrix(q), np.triu(M) + np.triu(M, 1).T, atol=1e-9)


def test_a_mimic_joint_s_torque_is_folded_onto_its_source() -> None:
    """With ``j3`` mimicking ``j1`` (q3 = 1.5 q1 + 0.2), the torques on ``q = (q1, q2)`` are those
    of the model where j3 moves freely, at the mimicked values, mapped back: tau1 + 1.5 tau3."""
    free = Kinematics.load(PRISMATIC_AND_FIXED).dynamics()
    mimic = Kinematics.load(
        PRISMATIC_AND_FIXED.replace(
            '<axis xyz="0.6 0 0.8"/><limit lower="-2" upper="2" effort="1" velocity="1"/>'
            "</joint></robot>",
            '<axis xyz="0.6 0 0.8"/><limit lower="-2" upper="2" effort="1" velocity="1"/>'
            '<mimic joint="j1" multiplier="1.5" offset="0.2"/></joint></robot>',
        )
    ).dynamics()
    assert mimic.n_v == 2
    rng = np.random.default_rng(5)
    for _ in range(5):
        q, v, a = (rng.uniform(-1.5, 1.5, 2) for _ in range(3))
        full = [np.array([x[0], x[1], 1.5 * x[0] + off]) for x, off in ((q, 0.2), (v, 0), (a, 0))]
        tau = free.rnea(*full)
        np.testing.assert_allclose(mimic.rnea(q, v, a), [tau[0] + 1.5 * tau[2], tau[1]], atol=1e-9)
        J = np.array([[1.0, 0.0], [0.0, 1.0], [1.5, 0.0]])
        np.testing.assert_allclose(
            mimic.mass_matrix(q), J.T @ free.mass_matrix(full[0]) @ J, atol=1e-9
        )
