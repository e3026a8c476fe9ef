"""Numerical IK on Panda and UR5 from random reachable targets."""

from __future__ import annotations

import numpy as np
import pytest

from robomodel.description import UnknownNameError
from robomodel.kinematics import Kinematics, KinematicsError
from robomodel.kinematics.se3 import log_rotation


def _check(kin: Kinematics, link: str, T: np.ndarray, q: np.ndarray, tol: float = 1e-6) -> None:
    assert np.all(q >= kin.lower) and np.all(q <= kin.upper)
    T_q = kin.fk_link(q, link)
    assert np.linalg.norm(T_q[:3, 3] - T[:3, 3]) <= tol
    assert np.linalg.norm(log_rotation(T[:3, :3] @ T_q[:3, :3].T)) <= tol


@pytest.mark.parametrize(("robot", "link"), [("panda", "panda_hand_tcp"), ("ur5", "tool0")])
def test_ik_reaches_random_targets(robot: str, link: str, request: pytest.FixtureRequest) -> None:
    kin: Kinematics = request.getfixturevalue(robot)
    targets = kin.fk(kin.random_q(60, seed=11), links=[link])[:, 0]
    for k, T in enumerate(targets):
        result = kin.ik(T, link, rng=k)
        assert result.success, (k, result)
        assert result.position_error_m <= 1e-6 and result.rotation_error_rad <= 1e-6
        _check(kin, link, T, result.q)
        assert not result.q.flags.writeable


def test_ik_position_only(panda: Kinematics) -> None:
    T = panda.fk_link(panda.random_q(seed=2), "panda_hand")
    T_far = T.copy()
    T_far[:3, :3] = np.eye(3)  # orientation that may not be reachable with this position
    result = panda.ik(T_far, "panda_hand", position_only=True, rng=0)
    assert result.success
    assert result.rotation_error_rad == 0.0
    np.testing.assert_allclose(panda.fk_link(result.q, "panda_hand")[:3, 3], T[:3, 3], atol=1e-6)


def test_ik_unreachable_reports_failure_inside_limits(ur5: Kinematics) -> None:
    T = np.eye(4)
    T[:3, 3] = [5.0, 0.0, 0.0]  # far beyond the ~0.95 m reach
    result = ur5.ik(T, "tool0", max_time_s=0.05, restarts=3, rng=0)
    assert not result.success
    assert result.position_error_m > 3.5
    assert np.all(result.q >= ur5.lower) and np.all(result.q <= ur5.upper)


def test_ik_batch(ur5: Kinematics) -> None:
    targets = ur5.fk(ur5.random_q(40, seed=4), links=["tool0"])[:, 0]
    result = ur5.ik_batch(targets, "tool0", rng=1)
    assert result.q.shape == (40, ur5.n_q)
    assert result.success.mean() >= 0.95
    for T, q, ok in zip(targets, result.q, result.success, strict=True):
        if ok:
            _check(ur5, "tool0", T, q)


def test_ik_respects_mimic_and_seed(panda: Kinematics) -> None:
    q0 = panda.random_q(seed=9)
    T = panda.fk_link(q0, "panda_rightfinger")
    result = panda.ik(T, "panda_rightfinger", seed=q0 + 0.01, rng=0)
    assert result.success
    assert result.iterations < 20


def test_ik_bad_input(panda: Kinematics) -> None:
    with pytest.raises(UnknownNameError, match="panda_hand"):
        panda.ik(np.eye(4), "panda_hnd")
    with pytest.raises(KinematicsError, match="4x4"):
        panda.ik(np.eye(3), "panda_hand")
    with pytest.raises(KinematicsError):
        panda.ik(np.full((4, 4), np.nan), "panda_hand")
