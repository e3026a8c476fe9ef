"""The one-configuration paths: MuJoCo fast path against the numpy reference, single against
batched, Jacobians against finite differences, IK's iteration budget."""

from __future__ import annotations

import threading

import numpy as np
import pytest

from robomodel.description import read_urdf
from robomodel.kinematics import ConfigurationError, Kinematics, KinematicsError
from robomodel.kinematics.se3 import log_rotation
from tests.conftest import example_robot_data_dir

pytest.importorskip("mujoco")

ROBOTS = [
    ("panda_description/urdf/panda.urdf", "panda_hand_tcp"),
    ("panda_description/urdf/panda.urdf", "panda_rightfinger"),  # mimic finger
    ("ur_description/urdf/ur5_robot.urdf", "tool0"),
    ("pr2_description/urdf/pr2.urdf", "r_gripper_tool_frame"),  # continuous + prismatic torso
    ("talos_data/robots/talos_reduced.urdf", "gripper_left_fingertip_3_link"),  # mimic
]


def _pair(relative: str) -> tuple[Kinematics, Kinematics]:
    robot = read_urdf(str(example_robot_data_dir() / relative)).robot
    return Kinematics(robot, backend="numpy"), Kinematics(robot, backend="mujoco")


@pytest.mark.parametrize(("relative", "link"), ROBOTS)
def test_mujoco_equals_numpy_and_single_equals_batch(relative: str, link: str) -> None:
    ref, fast = _pair(relative)
    assert (ref.backend, fast.backend) == ("numpy", "mujoco")
    Q = ref.random_q(4, seed=7)
    batch_fk = ref.fk(Q)
    point = np.array([0.03, -0.01, 0.02])
    for k, q in enumerate(Q):
        for kin in (ref, fast):
            np.testing.assert_allclose(kin.fk(q), batch_fk[k], rtol=0, atol=1e-12)
            np.testing.assert_allclose(
                kin.fk(q, links=[link, kin.root_link]),
                batch_fk[k][[kin.link_index(link), 0]],
                rtol=0,
                atol=1e-12,
            )
            np.testing.assert_allclose(
                kin.fk_link(q, link), batch_fk[k][kin.link_index(link)], rtol=0, atol=1e-12
            )
            for frame in ("world", "local"):
                for p in ((0.0, 0.0, 0.0), point):
                    J_batch = ref.jacobian(Q[k : k + 1], link, point=p, frame=frame)[0]
                    J = kin.jacobian(q, link, point=p, frame=frame)
                    np.testing.assert_allclose(J, J_batch, rtol=0, atol=1e-12)
                    assert not J.flags.writeable
        assert not fast.fk(q).flags.writeable and not fast.fk_link(q, link).flags.writeable


@pytest.mark.parametrize("backend", ["numpy", "mujoco"])
@pytest.mark.parametrize(("relative", "link"), ROBOTS[:4])
def test_single_jacobian_matches_finite_differences(relative: str, link: str, backend: str) -> None:
    kin = Kinematics(read_urdf(str(example_robot_data_dir() / relative)).robot, backend=backend)  # type: ignore[arg-type]
    point = np.array([0.01, -0.02, 0.03])
    eps = 1e-6
    for q in kin.random_q(2, seed=11):
        J = kin.jacobian(q, link, point=point)
        T0 = kin.fk_link(q, link)
        fd = np.zeros_like(J)
        for c in range(kin.n_q):
            dq = np.zeros(kin.n_q)
            dq[c] = eps
            Tp, Tm = kin.fk_link(q + dq, link), kin.fk_link(q - dq, link)
            fd[:3, c] = ((Tp[:3, :3] - Tm[:3, :3]) @ point + Tp[:3, 3] - Tm[:3, 3]) / (2 * eps)
            fd[3:, c] = (
                log_rotation(Tp[:3, :3] @ T0[:3, :3].T) - log_rotation(Tm[:3, :3] @ T0[:3, :3].T)
            ) / (2 * eps)
        np.testing.assert_allclose(J, fd, atol=1e-7)
        assert np.abs(J).max() > 0.1  # not vacuous


def test_backend_choice_and_fallback(tmp_path: object) -> None:
    urdf = """<robot name="float">
      <link name="world"/><link name="base"/><link name="arm"/>
      <joint name="free" type="floating"><parent link="world"/><child link="base"/></joint>
      <joint name="j" type="revolute"><parent link="base"/><child link="arm"/>
        <origin xyz="0 0 0.5"/><axis xyz="0 1 0"/>
        <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
    </robot>"""
    robot = read_urdf(urdf).robot
    auto = Kinematics(robot)
    assert auto.backend == "numpy"  # MuJoCo is not used for floating joints
    q = auto.neutral()
    q[:3] = [0.1, 0.2, 0.3]
    q[7] = 0.4
    np.testing.assert_allclose(auto.fk_link(q, "arm")[:3, 3], [0.1, 0.2, 0.8], atol=1e-15)
    with pytest.raises(KinematicsError, match="backend='mujoco'"):
        Kinematics(robot, backend="mujoco")
    with pytest.raises(ValueError, match="backend must be"):
        Kinematics(robot, backend="fast")  # type: ignore[arg-type]


def test_fast_path_checks_q_like_the_reference() -> None:
    _, fast = _pair("ur_description/urdf/ur5_robot.urdf")
    q = np.full(fast.n_q, 1e200)  # finite although q @ q overflows
    np.testing.assert_allclose(fast.fk(q), fast.fk(q[None])[0], atol=1e-9)
    q[3] = np.inf
    with pytest.raises(ConfigurationError, match="non-finite"):
        fast.fk_link(q, "tool0")
    with pytest.raises(ConfigurationError, match="shape"):
        fast.jacobian(np.zeros(3), "tool0")


def test_threads_get_their_own_scratch_data() -> None:
    ref, fast = _pair("panda_description/urdf/panda.urdf")
    Q = ref.random_q(400, seed=3)
    expected = ref.fk(Q)
    failures: list[int] = []

    def work(offset: int) -> None:
        for k in range(offset, len(Q), 4):
            T = fast.fk(Q[k])
            J = fast.jacobian(Q[k], "panda_hand")
            if not np.allclose(T, expected[k], atol=1e-12) or not np.allclose(
                J, ref.jacobian(Q[k], "panda_hand"), atol=1e-12
            ):
                failures.append(k)

    threads = [threading.Thread(target=work, args=(i,)) for i in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert failures == []


@pytest.mark.parametrize("backend", ["numpy", "mujoco"])
def test_ik_budget_is_iterations_and_results_are_reproducible(backend: str) -> None:
    path = str(example_robot_data_dir() / "ur_description/urdf/ur5_robot.urdf")
    kin = Kinematics(read_urdf(path).robot, backend=backend)  # type: ignore[arg-type]
    T = np.eye(4)
    T[:3, 3] = [5.0, 0.0, 0.0]  # unreachable: every attempt runs out
    result = kin.ik(T, "tool0", max_iterations=150, rng=0)
    assert not result.success
    assert result.iterations <= 150 and result.attempts >= 3
    assert np.all(result.q >= kin.lower) and np.all(result.q <= kin.upper)
    targets = kin.fk(kin.random_q(20, seed=5), links=["tool0"])[:, 0]
    for k, T in enumerate(targets):
        a = kin.ik(T, "tool0", rng=k)
        b = kin.ik(T, "tool0", rng=k)
        assert a.success and a.iterations == b.iterations
        np.testing.assert_array_equal(a.q, b.q)
    with pytest.raises(KinematicsError, match="max_iterations"):
        kin.ik(targets[0], "tool0", max_iterations=0)


def test_ik_backends_both_solve_the_mimic_finger() -> None:
    ref, fast = _pair("panda_description/urdf/panda.urdf")
    q0 = ref.random_q(seed=9)
    T = ref.fk_link(q0, "panda_rightfinger")
    for kin in (ref, fast):
        result = kin.ik(T, "panda_rightfinger", rng=0)
        assert result.success
        T_q = ref.fk_link(result.q, "panda_rightfinger")
        assert np.linalg.norm(T_q[:3, 3] - T[:3, 3]) <= 1e-6
        result = kin.ik(T, "panda_rightfinger", position_only=True, rng=0)
        assert result.success and result.rotation_error_rad == 0.0
