"""Forward kinematics: the pose of every link in the root frame.

Two implementations of the same formulas:

* :func:`fk_batch` keeps the batch in the *last* axis (``(n_links, 4, 4, batch)``) so that every
  step is a BLAS product ``K.T @ W`` over the whole batch plus a few element-wise updates of two
  rotation columns; the result is handed out as a transposed read-only view with the documented
  shape ``(batch, n_links, 4, 4)``.
* :func:`fk_single` serves one configuration: the local transforms of all joints are built at
  once with numpy, then chained with ``ndarray.dot`` (the cheapest 4x4 product call in numpy).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from robomodel.kinematics._compile import (
    FIXED,
    FLOATING,
    PLANAR,
    PRISMATIC,
    REVOLUTE,
    CompiledModel,
)
from robomodel.kinematics.se3 import axis_angle_matrix, matrix_from_quat_xyzw

__all__ = ["SinglePlan", "fk_batch", "fk_single", "local_transforms_batch", "make_single_plan"]

F64 = NDArray[np.float64]
_EYE4 = np.eye(4)
_EYE4.setflags(write=False)


def ancestors_closure(model: CompiledModel, links: Sequence[int]) -> list[int]:
    """Sorted indices of ``links`` and all their ancestors (the links FK must visit)."""
    needed: set[int] = set()
    for i in links:
        while i >= 0 and i not in needed:
            needed.add(i)
            i = model.parent[i]
    return sorted(needed)


def local_transforms_batch(model: CompiledModel, i: int, qT: F64) -> F64:
    """``(batch, 4, 4)`` motion of a floating or planar joint (after its origin)."""
    kind = model.kind[i]
    s = int(model.q_index[i])
    batch = qT.shape[1]
    X = np.zeros((batch, 4, 4))
    X[:, 3, 3] = 1.0
    if kind == FLOATING:
        quat = qT[s + 3 : s + 7].T
        X[:, :3, :3] = matrix_from_quat_xyzw(quat)
        X[:, :3, 3] = qT[s : s + 3].T
    elif kind == PLANAR:
        e = model.plane_basis[i]
        X[:, :3, :3] = axis_angle_matrix(model.axis[i], qT[s + 2])
        X[:, :3, 3] = qT[s][:, None] * e[0] + qT[s + 1][:, None] * e[1]
    return X


def cos_sin(angle_rad: F64) -> tuple[F64, F64]:
    """``cos`` and ``sin`` through the half-angle tangent.

    numpy's float64 ``tan`` is SIMD-vectorised while ``cos``/``sin`` are not (about 10x slower
    here); ``t = tan(x/2)`` gives both with a few products, accurate to a few ulp (at x = pi, t is
    huge but finite and the formulas still give -1 and ~1e-16).
    """
    t = np.tan(0.5 * angle_rad)
    t2 = t * t
    inv = 1.0 / (1.0 + t2)
    c = (1.0 - t2) * inv
    s = (t + t) * inv
    return c, s


def joint_values(model: CompiledModel, qT: F64, links: Sequence[int]) -> F64:
    """``(len(links), batch)`` joint values of 1-dof links (mimic joints resolved)."""
    idx = list(links)
    return qT[model.q_index[idx]] * model.scale[idx, None] + model.offset[idx, None]


def fk_batch(model: CompiledModel, q: F64, links: Sequence[int] | None = None) -> F64:
    """Poses ``(batch, n_out, 4, 4)`` for ``q`` of shape ``(batch, n_q)`` (validated already).

    ``links`` selects output links (indices); all links when None.
    """
    batch = q.shape[0]
    order = list(range(1, model.n_links)) if links is None else ancestors_closure(model, links)
    qT = np.ascontiguousarray(q.T)
    buf = np.zeros((model.n_links, 4, 4, batch))
    buf[:, 3, 3, :] = 1.0
    buf[0, :3] = np.eye(4)[:3, :, None]
    KT = np.swapaxes(model.K, 1, 2)
    revolute = [i for i in order if model.kind[i] == REVOLUTE]
    row_of = {i: r for r, i in enumerate(revolute)}
    if revolute:
        cos, sin = cos_sin(joint_values(model, qT, revolute))
    for i in order:
        if i == 0:
            continue
        W = buf[i, :3]
        np.matmul(KT[i], buf[model.parent[i], :3], out=W)
        kind = model.kind[i]
        if kind == FIXED:
            continue
        if kind == REVOLUTE:
            c, s = cos[row_of[i]], sin[row_of[i]]
            col0, col1 = W[:, 0], W[:, 1]
            old0 = col0.copy()
            col0 *= c
            col0 += s * col1
            col1 *= c
            col1 -= s * old0
            if model.tilted[i]:
                W[...] = np.matmul(model.Pt[i].T, W)
        elif kind == PRISMATIC:
            value = joint_values(model, qT, [i])[0]
            a = model.axis[i]
            W[:, 3] += value * (a[0] * W[:, 0] + a[1] * W[:, 1] + a[2] * W[:, 2])
        else:
            X = local_transforms_batch(model, i, qT)
            W[...] = np.einsum("rkb,bkc->rcb", W, X)
    out = buf if links is None else buf[list(links)]
    Ts: NDArray[np.float64] = out.transpose(3, 0, 1, 2)
    Ts.setflags(write=False)
    return Ts


@dataclass(frozen=True, slots=True)
class SinglePlan:
    """Constants of the one-configuration path, precomputed once per model.

    The local transforms (joint origin and motion) of all 1-dof links come from one product:
    ``[1, cos t, sin t, t] @ M`` with ``M`` stacking four constant 4x4 matrices per link
    (``A + cos(t) B + sin(t) C`` for a revolute link, ``K + d E`` for a prismatic one), then
    ``@ Pt`` for tilted axes. Fixed links use their constant origin.
    """

    fixed_locals: tuple[F64, ...]
    steps: tuple[tuple[int, int, int], ...]
    mov_q: NDArray[np.int64]
    mov_scale: F64 | None
    mov_offset: F64 | None
    coef: F64
    M: F64
    Pt: F64 | None
    other_links: tuple[int, ...]
    other_slots: tuple[int, ...]


def _readonly(a: F64) -> F64:
    a.setflags(write=False)
    return a


def make_single_plan(model: CompiledModel) -> SinglePlan:
    kinds = model.kind
    mov = [i for i in range(model.n_links) if kinds[i] in (REVOLUTE, PRISMATIC)]
    others = [i for i in range(model.n_links) if kinds[i] in (FLOATING, PLANAR)]
    fixed = [i for i in range(model.n_links) if i not in set(mov) | set(others)]
    K = model.K
    n = len(mov)
    M = np.zeros((n, 4, 4, 4))
    for r, i in enumerate(mov):
        if kinds[i] == REVOLUTE:
            M[r, 0] = K[i]
            M[r, 0, :, :2] = 0.0
            M[r, 1, :, :2] = K[i, :, :2]
            M[r, 2, :, 0] = K[i, :, 1]
            M[r, 2, :, 1] = -K[i, :, 0]
        else:
            M[r, 0] = K[i]
            M[r, 3, :3, 3] = model.Ka[i]
    tilted = any(model.tilted[i] for i in mov)
    # The local transforms list is [*movable, *fixed, *others]; slot[i] says where link i is.
    slot = {i: r for r, i in enumerate([*mov, *fixed, *others])}
    scale = model.scale[mov].reshape(-1, 1, 1)
    offset = model.offset[mov].reshape(-1, 1, 1)
    mimic = bool(np.any(scale != 1.0) or np.any(offset != 0.0))
    coef = np.zeros((n, 1, 4))
    coef[:, 0, 0] = 1.0
    return SinglePlan(
        fixed_locals=tuple(_readonly(K[i].copy()) for i in fixed),
        steps=tuple((model.parent[i], slot[i], i) for i in range(1, model.n_links)),
        mov_q=model.q_index[mov].reshape(-1, 1, 1),
        mov_scale=scale if mimic else None,
        mov_offset=offset if mimic else None,
        coef=_readonly(coef),
        M=_readonly(M.reshape(n, 4, 16)),
        Pt=_readonly(model.Pt[mov].copy()) if tilted else None,
        other_links=tuple(others),
        other_slots=tuple(slot[i] for i in others),
    )


def fk_single(model: CompiledModel, plan: SinglePlan, q: F64) -> F64:
    """Poses ``(n_links, 4, 4)`` for one validated configuration ``q`` of shape ``(n_q,)``."""
    t = q[plan.mov_q]
    if plan.mov_scale is not None and plan.mov_offset is not None:
        t = t * plan.mov_scale + plan.mov_offset
    coef = plan.coef.copy()
    np.cos(t, out=coef[:, :, 1:2])
    np.sin(t, out=coef[:, :, 2:3])
    coef[:, :, 3:4] = t
    L = np.matmul(coef, plan.M).reshape(-1, 4, 4)
    if plan.Pt is not None:
        L = np.matmul(L, plan.Pt)
    local = [*L, *plan.fixed_locals]
    if plan.other_links:
        qT = q[:, None]
        for i in plan.other_links:
            local.append(model.K[i] @ local_transforms_batch(model, i, qT)[0])
    out = np.empty((model.n_links, 4, 4))
    rows = list(out)
    rows[0][...] = _EYE4
    for p, k, i in plan.steps:
        rows[p].dot(local[k], out=rows[i])
    out.setflags(write=False)
    return out
