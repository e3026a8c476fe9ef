"""Numerical inverse kinematics: Levenberg-Marquardt inside the joint limits, with restarts.

Each iteration computes the target link's pose and the geometric Jacobian on the path to it
(:mod:`robomodel.kinematics._chain`), the error ``e = [p_target - p; log(R_target R^T)]``
(root-frame axes), and the damped step ``dq = J^T (J J^T + lambda I)^-1 e`` with
``lambda = 0.1 |e|^2 + 1e-9`` (Sugihara's error-dependent damping: large steps are damped
far from the target, Gauss-Newton's quadratic convergence is kept near it). Every iterate is
clamped to the limits, so a returned ``q`` never leaves them. An attempt that has not
converged after ``_MAX_ITERATIONS`` or stalls restarts from a random configuration. The budget
is a number of iterations (the result depends on the inputs and ``rng`` only, not on the
machine's load); a time limit is optional.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from robomodel.kinematics._chain import Chain, make_chain
from robomodel.kinematics._checks import check_q
from robomodel.kinematics._compile import CompiledModel
from robomodel.kinematics._mujoco import MujocoKinematics
from robomodel.kinematics.exceptions import KinematicsError
from robomodel.kinematics.fk import fk_batch, fk_single
from robomodel.kinematics.se3 import log_rotation

if TYPE_CHECKING:
    from robomodel.kinematics.kinematics import Kinematics

__all__ = ["IKBatchResult", "IKResult", "Solver", "solve_ik", "solve_ik_batch"]

F64 = NDArray[np.float64]

_MAX_ITERATIONS = 60
_MAX_STEP_RAD = 1.0  # per joint per iteration; keeps early steps inside the linear region
_DAMPING = 0.1  # lambda = _DAMPING * |e|^2 + 1e-9 (tuned on Panda and UR5)


@dataclass(frozen=True, slots=True)
class IKResult:
    """The outcome of one IK solve.

    Attributes:
        q: ``(n_q,)`` configuration, always inside the limits (the best one found).
        success: Both errors are within tolerance.
        position_error_m: Distance from the link origin to the target [m].
        rotation_error_rad: Angle of the remaining rotation [rad] (0 if ``position_only``).
        iterations: Iterations over all attempts.
        attempts: 1 + the number of random restarts used.
    """

    q: F64
    success: bool
    position_error_m: float
    rotation_error_rad: float
    iterations: int
    attempts: int


@dataclass(frozen=True, slots=True)
class IKBatchResult:
    """The outcome of a batched solve: one row per target (see :class:`IKResult`)."""

    q: F64
    success: NDArray[np.bool_]
    position_error_m: F64
    rotation_error_rad: F64
    iterations: NDArray[np.int64]


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


def solve_ik(
    kin: Kinematics,
    T_root_target: ArrayLike,
    link: str,
    *,
    seed: ArrayLike | None,
    position_only: bool,
    tol_m: float,
    tol_rad: float,
    max_iterations: int,
    max_time_s: float | None,
    restarts: int,
    rng: int | np.random.Generator | None,
) -> IKResult:
    """See :meth:`Kinematics.ik`."""
    T_t = _target(T_root_target)
    if T_t.shape != (4, 4):
        raise KinematicsError("ik takes one 4x4 target; use ik_batch for many")
    if max_iterations < 1:
        raise KinematicsError(f"max_iterations must be at least 1, not {max_iterations}")
    solver = kin._ik_solver(link, position_only)
    model = kin.compiled
    if seed is None:
        q = solver.start.copy()
    else:
        q = np.clip(np.array(check_q(model, seed), dtype=np.float64), model.lower, model.upper)
    active = solver.chain.active
    lower, upper = solver.lower, solver.upper
    evaluate, step = solver.error_and_jacobian, solver.step
    R_t, p_t = np.ascontiguousarray(T_t[:3, :3]), T_t[:3, 3].copy()
    deadline = None if max_time_s is None else time.perf_counter() + max_time_s
    gen = None  # made on the first restart: most targets need none
    # Only q[active] changes; each iterate qa is a new array, so the best is kept by reference.
    best_qa, best, best_cost = q[active], (math.inf, math.inf), math.inf
    total_iterations = 0
    attempts = 0
    while attempts <= restarts and total_iterations < max_iterations:
        attempts += 1
        qa = q[active]
        stall = 0
        last_cost = math.inf
        for _ in range(min(_MAX_ITERATIONS, max_iterations - total_iterations)):
            total_iterations += 1
            e, J, pe, re = evaluate(q, R_t, p_t)
            cost = pe + re
            if cost < best_cost:
                best_qa, best, best_cost = qa, (pe, re), cost
            if pe <= tol_m and re <= tol_rad:
                return _result(q, active, qa, True, pe, re, total_iterations, attempts)
            stall = stall + 1 if cost > 0.999 * last_cost else 0
            if stall >= 5:
                break
            last_cost = cost
            dq = step(J, e, _DAMPING * float(e @ e) + 1e-9)
            biggest = float(abs(dq).max())
            if biggest > _MAX_STEP_RAD:
                dq *= _MAX_STEP_RAD / biggest
            qa = qa + dq
            np.maximum(qa, lower, out=qa)
            np.minimum(qa, upper, out=qa)
            q[active] = qa
        if deadline is not None and time.perf_counter() > deadline:
            break
        if gen is None:
            gen = np.random.default_rng(rng)
        q[active] = gen.uniform(solver.sample_lo, solver.sample_hi)
    pe, re = best
    return _result(q, active, best_qa, False, pe, re, total_iterations, attempts)


def _result(
    q: F64,
    active: NDArray[np.int64],
    qa: F64,
    ok: bool,
    pe: float,
    re: float,
    iterations: int,
    attempts: int,
) -> IKResult:
    q = q.copy()
    q[active] = qa
    q.setflags(write=False)
    return IKResult(q, ok, pe, re, iterations, attempts)


def solve_ik_batch(
    kin: Kinematics,
    Ts_root_target: ArrayLike,
    link: str,
    *,
    seed: ArrayLike | None = None,
    position_only: bool = False,
    tol_m: float = 1e-6,
    tol_rad: float = 1e-6,
    max_iterations: int = 300,
    rng: int | np.random.Generator | None = None,
) -> IKBatchResult:
    """Solve many targets at once: the same iteration, vectorised over the targets.

    Targets that have not converged after ``_MAX_ITERATIONS`` iterations of an attempt restart
    from random configurations, until ``max_iterations`` in total.
    """
    T_t = _target(Ts_root_target)
    if T_t.ndim != 3:
        raise KinematicsError(f"ik_batch takes targets of shape (n, 4, 4), got {T_t.shape}")
    n = T_t.shape[0]
    model = kin.compiled
    chain = make_chain(model, model.link(link))
    solver = kin._ik_solver(link, position_only)
    gen = np.random.default_rng(rng)
    if seed is None:
        q = np.tile(np.clip(kin.neutral(), model.lower, model.upper), (n, 1))
        q[:, chain.active] = 0.5 * (solver.sample_lo + solver.sample_hi)
    else:
        q = np.array(np.broadcast_to(check_q(model, seed), (n, model.n_q)), dtype=np.float64)
        q = np.clip(q, model.lower, model.upper)
    done = np.zeros(n, dtype=bool)
    iterations = np.zeros(n, dtype=np.int64)
    pos_err = np.full(n, np.inf)
    rot_err = np.full(n, np.inf)
    last_cost = np.full(n, np.inf)
    stall = np.zeros(n, dtype=np.int64)
    attempt_iterations = np.zeros(n, dtype=np.int64)
    rows = 3 if position_only else 6
    rev = chain.revolute[None, :, None]
    sub = chain.model
    for _ in range(max_iterations):
        todo = np.flatnonzero(~done)
        if len(todo) == 0:
            break
        restart = todo[(stall[todo] >= 5) | (attempt_iterations[todo] >= _MAX_ITERATIONS)]
        if len(restart):
            q[np.ix_(restart, chain.active)] = gen.uniform(
                solver.sample_lo, solver.sample_hi, size=(len(restart), len(chain.active))
            )
            stall[restart] = 0
            attempt_iterations[restart] = 0
            last_cost[restart] = np.inf
        qs = q[todo]
        Ts = fk_batch(sub, qs, [*chain.movable.tolist(), sub.n_links - 1])
        T = Ts[:, -1]
        Tt = T_t[todo]
        ep = Tt[:, :3, 3] - T[:, :3, 3]
        pe = np.linalg.norm(ep, axis=1)
        er = log_rotation(Tt[:, :3, :3] @ np.swapaxes(T[:, :3, :3], 1, 2))
        re = np.zeros(len(todo)) if position_only else np.linalg.norm(er, axis=1)
        pos_err[todo], rot_err[todo] = pe, re
        iterations[todo] += 1
        attempt_iterations[todo] += 1
        cost = pe + re
        stall[todo] = np.where(cost > 0.999 * last_cost[todo], stall[todo] + 1, 0)
        last_cost[todo] = cost
        ok = (pe <= tol_m) & (re <= tol_rad)
        done[todo[ok]] = True
        keep = ~ok
        if not keep.any():
            break
        todo, qs, Ts, T, ep, er = todo[keep], qs[keep], Ts[keep], T[keep], ep[keep], er[keep]
        Tm = Ts[:, :-1]
        z = np.einsum("bmij,mj->bmi", Tm[..., :3, :3], chain.axis)
        r = T[:, None, :3, 3] - Tm[..., :3, 3]
        lin = np.where(rev, np.cross(z, r), z)
        J = np.concatenate([lin, np.where(rev, z, 0.0)], axis=2)[..., :rows]
        J = np.swapaxes(J, 1, 2) @ chain.S
        e = ep if position_only else np.concatenate([ep, er], axis=1)
        damping = _DAMPING * np.einsum("bi,bi->b", e, e) + 1e-9
        A = J @ np.swapaxes(J, 1, 2) + damping[:, None, None] * np.eye(rows)
        y = np.linalg.solve(A, e[:, :, None])
        dq = (np.swapaxes(J, 1, 2) @ y)[:, :, 0]
        biggest = np.max(np.abs(dq), axis=1, keepdims=True)
        dq *= np.minimum(1.0, _MAX_STEP_RAD / np.maximum(biggest, 1e-300))
        qa = np.clip(qs[:, chain.active] + dq, solver.lower, solver.upper)
        q[np.ix_(todo, chain.active)] = qa
    q.setflags(write=False)
    return IKBatchResult(q, done, pos_err, rot_err, iterations)
