"""The per-(model, link) IK solver constants and what single and batched solves share.

See :mod:`robomodel.kinematics.ik` for the algorithm.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from robomodel.kinematics._chain import Chain, make_chain
from robomodel.kinematics._checks import check_q
from robomodel.kinematics._compile import CompiledModel
from robomodel.kinematics._mujoco import MujocoKinematics
from robomodel.kinematics.exceptions import KinematicsError
from robomodel.kinematics.fk import fk_single
from robomodel.kinematics.se3 import log_rotation

__all__ = ["Solver"]

F64 = NDArray[np.float64]

_MAX_ITERATIONS = 60
_MAX_STEP_RAD = 1.0  # per joint per iteration; keeps early steps inside the linear region
_DAMPING = 0.1  # lambda = _DAMPING * |e|^2 + 1e-9 (tuned on Panda and UR5)

_STALL_RATIO = 0.999  # an iteration that lowers the cost by less than 0.1% is a stall
_STALL_LIMIT = 5  # stalls in a row that end an attempt


def _target(T_root_target: ArrayLike) -> F64:
    T = np.asarray(T_root_target, dtype=np.float64)
    if T.shape[-2:] != (4, 4) or not np.isfinite(T).all():
        raise KinematicsError(f"the target must be finite 4x4 poses, got shape {T.shape}")
    return T


def _log3(R: list[list[float]]) -> tuple[float, float, float]:
    """Rotation vector of a 3x3 rotation given as nested lists (scalar code; near pi via
    quaternions)."""
    (r00, r01, r02), (r10, r11, r12), (r20, r21, r22) = R
    cos_angle = 0.5 * (r00 + r11 + r22 - 1.0)
    vx, vy, vz = r21 - r12, r02 - r20, r10 - r01
    if cos_angle > 0.999999:
        # sin(angle) ~ angle: rotation vector = v / 2 to third order.
        return 0.5 * vx, 0.5 * vy, 0.5 * vz
    if cos_angle < -0.99:
        w = log_rotation(np.array(R))
        return float(w[0]), float(w[1]), float(w[2])
    angle = math.acos(cos_angle)
    k = angle / (2.0 * math.sin(angle))
    return k * vx, k * vy, k * vz


class Solver:
    """Per-(model, link) constants for single-target solves.

    ``error_and_jacobian`` evaluates the path to the link with MuJoCo when ``mujoco`` is given
    (see :mod:`robomodel.kinematics._mujoco`), else with the numpy reference.
    """

    def __init__(
        self,
        model: CompiledModel,
        link: str,
        position_only: bool,
        neutral: F64,
        mujoco: Any = None,
    ) -> None:
        self.chain: Chain = make_chain(model, model.link(link))
        c = self.chain
        self.lower = np.where(np.isfinite(model.lower), model.lower, -np.inf)[c.active]
        self.upper = np.where(np.isfinite(model.upper), model.upper, np.inf)[c.active]
        self.sample_lo = np.where(np.isfinite(self.lower), self.lower, -math.pi)
        self.sample_hi = np.where(np.isfinite(self.upper), self.upper, math.pi)
        self.rev = c.revolute.astype(np.float64)[:, None]
        self.position_only = position_only
        self.rows = 3 if position_only else 6
        self.eye = np.eye(self.rows)
        #: The default first configuration: the middle of the limits on the path.
        self.start = np.clip(neutral, model.lower, model.upper)
        self.start[c.active] = 0.5 * (self.sample_lo + self.sample_hi)
        self.start.setflags(write=False)
        fast = None
        if mujoco is not None:
            try:
                fast = MujocoKinematics(c.model, mujoco)
            except ValueError:
                fast = None
        self.backend = "numpy" if fast is None else "mujoco"
        self.error_and_jacobian = self._numpy_error_and_jacobian
        self.step = self._numpy_step
        if fast is not None:
            S = fast.S[:, c.active]
            self._S_fast = None if np.array_equal(S, np.eye(*S.shape)) else S
            self._pose_and_jacobian = fast.pose_and_jacobian
            self.error_and_jacobian = self._mujoco_error_and_jacobian
            self._mujoco = mujoco
            self._y = np.empty(self.rows)
            self.step = self._mujoco_step

    def _numpy_step(self, J: F64, e: F64, damping: float) -> F64:
        """The damped least-squares step ``J^T (J J^T + damping I)^-1 e``."""
        dq: F64 = J.T @ np.linalg.solve(J @ J.T + damping * self.eye, e)
        return dq

    def _mujoco_step(self, J: F64, e: F64, damping: float) -> F64:
        """The same step with MuJoCo's dense Cholesky (the matrix is symmetric positive
        definite: damping > 0), a third of ``np.linalg.solve``'s call overhead."""
        A = J @ J.T
        A.flat[:: self.rows + 1] += damping
        self._mujoco.mju_cholFactor(A, 1e-15)
        self._mujoco.mju_cholSolve(self._y, A, e)
        dq: F64 = J.T @ self._y
        return dq

    def _mujoco_error_and_jacobian(
        self, q: F64, R_t: F64, p_t: F64
    ) -> tuple[F64, F64, float, float]:
        R, p, J_mj = self._pose_and_jacobian(q, self.chain.model.n_links - 1, None)
        J = J_mj if self._S_fast is None else J_mj @ self._S_fast
        ex, ey, ez = (p_t - p).tolist()
        pos_err = math.sqrt(ex * ex + ey * ey + ez * ez)
        if self.position_only:
            return np.array((ex, ey, ez)), J[:3], pos_err, 0.0
        rx, ry, rz = _log3((R_t @ R.T).tolist())
        rot_err = math.sqrt(rx * rx + ry * ry + rz * rz)
        return np.array((ex, ey, ez, rx, ry, rz)), J, pos_err, rot_err

    def _numpy_error_and_jacobian(
        self, q: F64, R_t: F64, p_t: F64
    ) -> tuple[F64, F64, float, float]:
        c = self.chain
        Ts = fk_single(c.model, c.plan, q)
        T = Ts[-1]
        ep = p_t - T[:3, 3]
        pos_err = math.sqrt(float(ep @ ep))
        Tm = Ts[c.movable]
        z = (Tm[:, :3, :3] @ c.axis[:, :, None])[:, :, 0]
        r = T[:3, 3] - Tm[:, :3, 3]
        lin = np.empty_like(z)
        lin[:, 0] = z[:, 1] * r[:, 2] - z[:, 2] * r[:, 1]
        lin[:, 1] = z[:, 2] * r[:, 0] - z[:, 0] * r[:, 2]
        lin[:, 2] = z[:, 0] * r[:, 1] - z[:, 1] * r[:, 0]
        lin = self.rev * lin + (1.0 - self.rev) * z
        if self.position_only:
            return ep, (lin.T @ c.S), pos_err, 0.0
        er = _log3((R_t @ T[:3, :3].T).tolist())
        e = np.array([ep[0], ep[1], ep[2], er[0], er[1], er[2]])
        J = np.empty((6, c.S.shape[1]))
        J[:3] = lin.T @ c.S
        J[3:] = (self.rev * z).T @ c.S
        rot_err = math.sqrt(er[0] * er[0] + er[1] * er[1] + er[2] * er[2])
        return e, J, pos_err, rot_err


def _initial_q(
    solver: Solver, model: CompiledModel, seed: ArrayLike | None, n_targets: int | None = None
) -> F64:
    """The first configuration, or one per target when ``n_targets`` is given.

    Without a seed this is ``solver.start`` (the middle of the limits on the path); a seed is
    clamped to the limits, since every iterate must stay inside them.
    """
    if n_targets is None:
        if seed is None:
            start: F64 = solver.start.copy()
            return start
        return np.clip(np.array(check_q(model, seed), dtype=np.float64), model.lower, model.upper)
    if seed is None:
        return np.tile(solver.start, (n_targets, 1))
    q = np.array(np.broadcast_to(check_q(model, seed), (n_targets, model.n_q)), dtype=np.float64)
    return np.clip(q, model.lower, model.upper)
