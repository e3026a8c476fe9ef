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
