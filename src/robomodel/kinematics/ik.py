"""Numerical inverse kinematics: Levenberg-Marquardt inside the joint limits, with restarts.

Each iteration computes the target link's pose and the geometric Jacobian on the path to it
(:mod:`robomodel.kinematics._chain`), the error ``e = [p_target - p; log(R_target R^T)]``
(root-frame axes), and the damped step ``dq = J^T (J J^T + lambda I)^-1 e`` with
``lambda = 0.1 |e|^2 + 1e-9`` (Sugihara's error-dependent damping: large steps are damped
far from the target, Gauss-Newton's quadratic convergence is kept near it). Every iterate is
clamped to the limits, so a returned ``q`` never leaves them. An attempt that has not
converged after ``_MAX_ITERATIONS`` or stalls restarts from a random configuration. The budget
is a number of iterations (the result depends on the inputs and ``rng`` only, not on the
machine's load); a time limit is optional. The options and their defaults are
:class:`~robomodel.kinematics.IKOptions`.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from robomodel.kinematics._compile import CompiledModel
from robomodel.kinematics._ik_batch import IKBatchResult, solve_ik_batch
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

__all__ = ["IKBatchResult", "IKOptions", "IKResult", "Solver", "solve_ik", "solve_ik_batch"]

F64 = NDArray[np.float64]


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
class _Attempt:
    """What one attempt found: its iterations and its best iterate.

    Attributes:
        iterations: Iterations the attempt ran.
        converged: The best iterate is within both tolerances.
        best_qa: ``q[active]`` with the lowest ``position_error_m + rotation_error_rad`` (the
            first such), or the start when no cost was finite.
        position_error_m, rotation_error_rad: The errors at ``best_qa`` (infinite when no cost
            was finite).
    """

    iterations: int
    converged: bool
    best_qa: F64
    position_error_m: float
    rotation_error_rad: float

    @property
    def cost(self) -> float:
        return self.position_error_m + self.rotation_error_rad


def _run_attempt(
    solver: Solver, q: F64, T_t: tuple[F64, F64], budget: int, tol_m: float, tol_rad: float
) -> _Attempt:
    """Iterate from ``q`` (updated in place) until converged, stalled or ``budget`` is spent.

    ``T_t`` is the target as ``(R_root_target, p_root_target)``. This is the hot loop of
    :func:`solve_ik`: scalar code, locals only.
    """
    active, lower, upper = solver.chain.active, solver.lower, solver.upper
    evaluate, step = solver.error_and_jacobian, solver.step
    R_t, p_t = T_t
    # Only q[active] changes; each iterate qa is a new array, so the best is kept by reference.
    qa = best_qa = q[active]
    best, best_cost = (math.inf, math.inf), math.inf
    stall = 0
    last_cost = math.inf
    iterations = 0
    for _ in range(budget):
        iterations += 1
        e, J, pe, re = evaluate(q, R_t, p_t)
        cost = pe + re
        if cost < best_cost:
            best_qa, best, best_cost = qa, (pe, re), cost
        if pe <= tol_m and re <= tol_rad:
            return _Attempt(iterations, True, qa, pe, re)
        stall = stall + 1 if cost > _STALL_RATIO * last_cost else 0
        if stall >= _STALL_LIMIT:
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
    return _Attempt(iterations, False, best_qa, *best)


def solve_ik(
    solver: Solver,
    model: CompiledModel,
    T_root_target: ArrayLike,
    *,
    seed: ArrayLike | None,
    rng: int | np.random.Generator | None,
    options: IKOptions,
) -> IKResult:
    """One target with ``solver`` (made for ``options.position_only``); see
    :meth:`Kinematics.ik`."""
    T_t = _target(T_root_target)
    if T_t.shape != (4, 4):
        raise KinematicsError("ik takes one 4x4 target; use ik_batch for many")
    if solver.position_only != options.position_only:
        raise KinematicsError("the solver and the options disagree on position_only")
    max_iterations, max_time_s = options.max_iterations, options.max_time_s
    tol_m, tol_rad = options.tol_m, options.tol_rad
    q = _initial_q(solver, model, seed)
    active = solver.chain.active
    target = (np.ascontiguousarray(T_t[:3, :3]), T_t[:3, 3].copy())
    deadline = None if max_time_s is None else time.perf_counter() + max_time_s
    gen = None  # made on the first restart: most targets need none
    best = _Attempt(0, False, q[active], math.inf, math.inf)
    total_iterations = 0
    attempts = 0
    while attempts <= options.restarts and total_iterations < max_iterations:
        attempts += 1
        budget = min(_MAX_ITERATIONS, max_iterations - total_iterations)
        attempt = _run_attempt(solver, q, target, budget, tol_m, tol_rad)
        total_iterations += attempt.iterations
        if attempt.converged or attempt.cost < best.cost:
            best = attempt
        if attempt.converged:
            break
        if deadline is not None and time.perf_counter() > deadline:
            break
        if gen is None:
            gen = np.random.default_rng(rng)
        q[active] = gen.uniform(solver.sample_lo, solver.sample_hi)
    return _result(q, active, best, total_iterations, attempts)


def _result(
    q: F64, active: NDArray[np.int64], best: _Attempt, iterations: int, attempts: int
) -> IKResult:
    """``q`` with ``best``'s values on the path, read-only, as an :class:`IKResult`."""
    q = q.copy()
    q[active] = best.best_qa
    q.setflags(write=False)
    return IKResult(
        q,
        best.converged,
        best.position_error_m,
        best.rotation_error_rad,
        iterations,
        attempts,
    )
