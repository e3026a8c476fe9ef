"""Batched inverse kinematics: :mod:`robomodel.kinematics.ik`'s iteration, vectorised over
the targets."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from robomodel.kinematics._chain import Chain
from robomodel.kinematics._compile import CompiledModel
from robomodel.kinematics._ik_options import IKOptions
from robomodel.kinematics._ik_solver import (
    _DAMPING,
    _MAX_ITERATIONS,
    _MAX_STEP_RAD,
    _STALL_LIMIT,
    _STALL_RATIO,
    Solver,
    _initial_q,
    _target,
)
from robomodel.kinematics.exceptions import KinematicsError
from robomodel.kinematics.fk import fk_batch
from robomodel.kinematics.se3 import log_rotation

__all__ = ["IKBatchResult", "solve_ik_batch"]

F64 = NDArray[np.float64]


@dataclass(frozen=True, slots=True)
class IKBatchResult:
    """The outcome of a batched solve: one row per target (see
    :class:`~robomodel.kinematics.ik.IKResult`)."""

    q: F64
    success: NDArray[np.bool_]
    position_error_m: F64
    rotation_error_rad: F64
    iterations: NDArray[np.int64]


@dataclass(frozen=True, slots=True)
class _BatchState:
    """Per-target bookkeeping of :func:`solve_ik_batch` (arrays updated in place).

    Attributes:
        done: The target is within both tolerances.
        iterations: Iterations spent on the target over all attempts.
        pos_err, rot_err: Errors at the last iterate [m], [rad].
        last_cost: ``pos_err + rot_err`` before the last iteration, for stall detection.
        stall: Stalled iterations in a row in the current attempt.
        attempt_iterations: Iterations in the current attempt.
    """

    done: NDArray[np.bool_]
    iterations: NDArray[np.int64]
    pos_err: F64
    rot_err: F64
    last_cost: F64
    stall: NDArray[np.int64]
    attempt_iterations: NDArray[np.int64]

    @classmethod
    def start(cls, n_targets: int) -> _BatchState:
        return cls(
            done=np.zeros(n_targets, dtype=bool),
            iterations=np.zeros(n_targets, dtype=np.int64),
            pos_err=np.full(n_targets, np.inf),
            rot_err=np.full(n_targets, np.inf),
            last_cost=np.full(n_targets, np.inf),
            stall=np.zeros(n_targets, dtype=np.int64),
            attempt_iterations=np.zeros(n_targets, dtype=np.int64),
        )

    def restart_stalled(
        self, todo: NDArray[np.intp], q: F64, solver: Solver, gen: np.random.Generator
    ) -> None:
        """Restart the targets in ``todo`` that stalled or spent an attempt's budget, from
        random configurations (as :func:`solve_ik` does)."""
        ended = (self.stall[todo] >= _STALL_LIMIT) | (
            self.attempt_iterations[todo] >= _MAX_ITERATIONS
        )
        restart = todo[ended]
        if len(restart):
            active = solver.chain.active
            q[np.ix_(restart, active)] = gen.uniform(
                solver.sample_lo, solver.sample_hi, size=(len(restart), len(active))
            )
            self.stall[restart] = 0
            self.attempt_iterations[restart] = 0
            self.last_cost[restart] = np.inf

    def record(self, todo: NDArray[np.intp], pe: F64, re: F64, ok: NDArray[np.bool_]) -> None:
        """Count one iteration of the targets in ``todo``, with their errors and successes."""
        self.pos_err[todo], self.rot_err[todo] = pe, re
        self.iterations[todo] += 1
        self.attempt_iterations[todo] += 1
        cost = pe + re
        self.stall[todo] = np.where(
            cost > _STALL_RATIO * self.last_cost[todo], self.stall[todo] + 1, 0
        )
        self.last_cost[todo] = cost
        self.done[todo[ok]] = True


def _batch_errors(Ts_root_target: F64, T_root_link: F64, position_only: bool) -> tuple[F64, ...]:
    """Position and rotation errors per target, as vectors ``ep``, ``er`` (root-frame axes)
    and norms ``pe`` [m], ``re`` [rad] (``re`` zero when ``position_only``)."""
    ep = Ts_root_target[:, :3, 3] - T_root_link[:, :3, 3]
    pe = np.linalg.norm(ep, axis=1)
    er = log_rotation(Ts_root_target[:, :3, :3] @ np.swapaxes(T_root_link[:, :3, :3], 1, 2))
    re = np.zeros(len(ep)) if position_only else np.linalg.norm(er, axis=1)
    return ep, er, pe, re


def _batch_step(chain: Chain, Ts_root_path: F64, ep: F64, er: F64, position_only: bool) -> F64:
    """The damped least-squares step per target (as :func:`solve_ik`'s), at most
    ``_MAX_STEP_RAD`` per joint.

    ``Ts_root_path`` holds the poses of the chain's movable joints' child links, then of the
    target link: ``(n_targets, n_movable + 1, 4, 4)``.
    """
    rows = 3 if position_only else 6
    rev = chain.revolute[None, :, None]
    T = Ts_root_path[:, -1]
    Tm = Ts_root_path[:, :-1]
    z = np.einsum("bmij,mj->bmi", Tm[..., :3, :3], chain.axis)
    r = T[:, None, :3, 3] - Tm[..., :3, 3]
    lin = np.where(rev, np.cross(z, r), z)
    J = np.concatenate([lin, np.where(rev, z, 0.0)], axis=2)[..., :rows]
    J = np.swapaxes(J, 1, 2) @ chain.S
    e = ep if position_only else np.concatenate([ep, er], axis=1)
    damping = _DAMPING * np.einsum("bi,bi->b", e, e) + 1e-9
    A = J @ np.swapaxes(J, 1, 2) + damping[:, None, None] * np.eye(rows)
    y = np.linalg.solve(A, e[:, :, None])
    dq: F64 = (np.swapaxes(J, 1, 2) @ y)[:, :, 0]
    biggest = np.max(np.abs(dq), axis=1, keepdims=True)
    dq *= np.minimum(1.0, _MAX_STEP_RAD / np.maximum(biggest, 1e-300))
    return dq


def solve_ik_batch(
    solver: Solver,
    model: CompiledModel,
    Ts_root_target: ArrayLike,
    *,
    seed: ArrayLike | None,
    rng: int | np.random.Generator | None,
    options: IKOptions,
) -> IKBatchResult:
    """Solve many targets at once with ``solver`` (made for ``options.position_only``): the
    same iteration, vectorised over the targets.

    Targets that have not converged after ``_MAX_ITERATIONS`` iterations of an attempt restart
    from random configurations, until ``options.max_iterations`` per target in total
    (``options.restarts`` does not bound a batch; ``options.max_time_s`` must be None).
    """
    T_t = _target(Ts_root_target)
    if T_t.ndim != 3:
        raise KinematicsError(f"ik_batch takes targets of shape (n, 4, 4), got {T_t.shape}")
    if options.max_time_s is not None:
        raise KinematicsError("ik_batch has no time limit; pass max_time_s=None (the default)")
    if solver.position_only != options.position_only:
        raise KinematicsError("the solver and the options disagree on position_only")
    position_only, tol_m, tol_rad = options.position_only, options.tol_m, options.tol_rad
    n = T_t.shape[0]
    chain, sub = solver.chain, solver.chain.model
    gen = np.random.default_rng(rng)
    q = _initial_q(solver, model, seed, n)
    state = _BatchState.start(n)
    for _ in range(options.max_iterations):
        todo = np.flatnonzero(~state.done)
        if len(todo) == 0:
            break
        state.restart_stalled(todo, q, solver, gen)
        qs = q[todo]
        Ts = fk_batch(sub, qs, [*chain.movable.tolist(), sub.n_links - 1])
        ep, er, pe, re = _batch_errors(T_t[todo], Ts[:, -1], position_only)
        ok = (pe <= tol_m) & (re <= tol_rad)
        state.record(todo, pe, re, ok)
        keep = ~ok
        if not keep.any():
            break
        todo, qs = todo[keep], qs[keep]
        dq = _batch_step(chain, Ts[keep], ep[keep], er[keep], position_only)
        qa = np.clip(qs[:, chain.active] + dq, solver.lower, solver.upper)
        q[np.ix_(todo, chain.active)] = qa
    q.setflags(write=False)
    return IKBatchResult(q, state.done, state.pos_err, state.rot_err, state.iterations)
