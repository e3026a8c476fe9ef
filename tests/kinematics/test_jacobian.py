"""Jacobians against finite differences and pinocchio."""

from __future__ import annotations

import numpy as np
import pinocchio
import pytest

from robomodel.description import read_urdf
from robomodel.kinematics import Kinematics
from robomodel.kinematics.se3 import log_rotation
from tests.conftest import example_robot_data_dir
from tests.kinematics._pin import pin_q

ROBOTS = [
    ("panda_description/urdf/panda.urdf", "panda_hand_tcp"),
    ("panda_description/urdf/panda.urdf", "panda_rightfinger"),  # mimic finger
    ("ur_description/urdf/ur5_robot.urdf", "tool0"),
    ("pr2_description/urdf/pr2.urdf", "r_gripper_tool_frame"),  # continuous + prismatic torso
    ("talos_data/robots/talos_reduced.urdf", "gripper_left_fingertip_3_link"),  # mimic
]


def _fd_jacobian(kin: Kinematics, q: np.ndarray, link: str, point: np.ndarray) -> np.ndarray:
    eps = 1e-6
    J = np.zeros((6, kin.n_q))
    T0 = kin.fk_link(q, link)
    for k in range(kin.n_q):
        dq = np.zeros(kin.n_q)
        dq[k] = eps
        T1 = kin.fk_link(q + dq, link)
        Tm = kin.fk_link(q - dq, link)
        p1 = T1[:3, :3] @ point + T1[:3, 3]
        pm = Tm[:3, :3] @ point + Tm[:3, 3]
        J[:3, k] = (p1 - pm) / (2 * eps)
        J[3:, k] = (
            log_rotation(T1[:3, :3] @ T0[:3, :3].T) - log_rotation(Tm[:3, :3] @ T0[:3, :3].T)
        ) / (2 * eps)
    return J


@pytest.mark.parametrize(("relative", "link"), ROBOTS)
def test_jacobian_matches_finite_differences(relative: str, link: str) -> None:
    kin = Kinematics(read_urdf(str(example_robot_data_dir() / relative)).robot)
    rng = np.random.default_rng(3)
    point = np.array([0.01, -0.02, 0.03])
    for q in kin.random_q(3, seed=rng):
        J = kin.jacobian(q, link, point=point)
        np.testing.assert_allclose(J, _fd_jacobian(kin, q, link, point), atol=1e-7)
        R = kin.fk_link(q, link)[:3, :3]
        J_local = kin.jacobian(q, link, point=point, frame="local")
        np.testing.assert_allclose(J_local[:3], R.T @ J[:3], atol=1e-12)
        np.testing.assert_allclose(J_local[3:], R.T @ J[3:], atol=1e-12)


@pytest.mark.parametrize(("relative", "link"), ROBOTS[:3])
def test_jacobian_matches_pinocchio(relative: str, link: str) -> None:
    path = str(example_robot_data_dir() / relative)
    kin = Kinematics(read_urdf(path).robot)
    model = pinocchio.buildModelFromUrdf(path)
    data = model.createData()
    fid = model.getFrameId(link, pinocchio.BODY)
    for q in kin.random_q(3, seed=5):
        qp = pin_q(kin, model, q)
        for ref, ours in (("LOCAL_WORLD_ALIGNED", "world"), ("LOCAL", "local")):
            J_pin = pinocchio.computeFrameJacobian(
                model, data, qp, fid, getattr(pinocchio.ReferenceFrame, ref)
            )
            # pinocchio's columns follow its velocity vector; ours follow q (mimic folded in).
            J_ours = kin.jacobian(q, link, frame=ours)
            expected = np.zeros_like(J_ours)
            for jid in range(1, model.njoints):
                name = model.names[jid]
                col = J_pin[:, model.joints[jid].idx_v]
                if name in kin.mimic:
                    source, factor, _ = kin.mimic[name]
                    expected[:, kin.q_slice(source).start] += factor * col
                else:
                    expected[:, kin.q_slice(name).start] += col
            np.testing.assert_allclose(J_ours, expected, atol=1e-10)


def test_jacobian_is_batched_and_read_only(panda: Kinematics) -> None:
    qs = panda.random_q(6, seed=1).reshape(2, 3, -1)
    J = panda.jacobian(qs, "panda_hand")
    assert J.shape == (2, 3, 6, panda.n_q)
    np.testing.assert_allclose(J[1, 2], panda.jacobian(qs[1, 2], "panda_hand"), atol=1e-14)
    with pytest.raises(ValueError):
        J[0, 0, 0, 0] = 1.0
