"""Geometric Jacobians of a point fixed on a link.

Rows are ``[linear; angular]`` (pinocchio's order), columns follow ``q``. A mimic joint adds
``multiplier`` times its own column to its source joint's column. ``frame="world"`` gives the
velocity of the point and the angular velocity in root-frame axes (pinocchio's
``LOCAL_WORLD_ALIGNED``); ``frame="local"`` expresses both in the link's axes (``LOCAL``).
"""

from __future__ import annotations

from typing import Literal

import numpy as np
from numpy.typing import NDArray

from robomodel.kinematics._chain import Chain
from robomodel.kinematics._compile import PRISMATIC, REVOLUTE, CompiledModel
from robomodel.kinematics.exceptions import KinematicsError
from robomodel.kinematics.fk import ancestors_closure, fk_batch, fk_single

__all__ = ["JacobianFrame", "chain_columns", "jacobian_batch", "jacobian_single", "to_frame"]

F64 = NDArray[np.float64]
JacobianFrame = Literal["world", "local"]


def chain_columns(model: CompiledModel, link: int) -> tuple[list[int], F64]:
    """Movable links on the path to ``link`` and the ``(n_path, n_q)`` map to ``q`` columns."""
    path = ancestors_closure(model, [link])
    movable = [i for i in path if model.q_index[i] >= 0]
    for i in movable:
        if model.kind[i] not in (REVOLUTE, PRISMATIC):
            raise KinematicsError(
                f"Jacobians through the {('floating', 'planar')[model.kind[i] - 3]} joint "
                f"'{model.link_joint[i]}' are not supported"
            )
    S = np.zeros((len(movable), model.n_q))
    for row, i in enumerate(movable):
        S[row, model.q_index[i]] += model.scale[i]
    return movable, S


def jacobian_batch(
    model: CompiledModel,
    q: F64,
    link: int,
    point: F64,
    frame: JacobianFrame,
) -> F64:
    """``(batch, 6, n_q)`` Jacobians for validated ``q`` of shape ``(batch, n_q)``."""
    movable, S = chain_columns(model, link)
    out_links = [*movable, link]
    Ts = fk_batch(model, q, out_links)
    T_link = Ts[:, -1]
    p = T_link[:, :3, :3] @ point + T_link[:, :3, 3]
    J_path = np.zeros((q.shape[0], 6, len(movable)))
    if movable:
        Tj = Ts[:, :-1]
        z = np.einsum("bmij,mj->bmi", Tj[..., :3, :3], model.axis[movable])
        rev = np.array([model.kind[i] == REVOLUTE for i in movable])
        r = p[:, None, :] - Tj[..., :3, 3]
        lin = np.where(rev[None, :, None], np.cross(z, r), z)
        ang = np.where(rev[None, :, None], z, 0.0)
        J_path[:, :3] = np.swapaxes(lin, 1, 2)
        J_path[:, 3:] = np.swapaxes(ang, 1, 2)
    J = J_path @ S
    if frame == "local":
        Rt = np.swapaxes(T_link[:, :3, :3], 1, 2)
        J = np.concatenate([Rt @ J[:, :3], Rt @ J[:, 3:]], axis=1)
    elif frame != "world":
        raise ValueError(f"frame must be 'world' or 'local', not {frame!r}")
    return J


def jacobian_single(chain: Chain, q: F64, point: F64 | None, frame: JacobianFrame) -> F64:
    """``(6, n_q)`` Jacobian for one validated ``q`` of shape ``(n_q,)``.

    The same formulas as :func:`jacobian_batch`, on the path to the link only (``chain``) and
    without the batch axis: one FK of the path and a few small products.
    """
    Ts = fk_single(chain.model, chain.plan, q)
    T = Ts[-1]
    R = T[:3, :3]
    p = T[:3, 3] if point is None else R @ point + T[:3, 3]
    J = np.zeros((6, q.shape[0]))
    if len(chain.movable):
        Tm = Ts[chain.movable]
        z = (Tm[:, :3, :3] @ chain.axis[:, :, None])[:, :, 0]
        r = p - Tm[:, :3, 3]
        rev = chain.revolute
        J_path = np.empty((6, len(z)))
        J_path[0] = z[:, 1] * r[:, 2] - z[:, 2] * r[:, 1]
        J_path[1] = z[:, 2] * r[:, 0] - z[:, 0] * r[:, 2]
        J_path[2] = z[:, 0] * r[:, 1] - z[:, 1] * r[:, 0]
        J_path[3:] = z.T
        if not rev.all():
            J_path[:3, ~rev] = z[~rev].T
            J_path[3:, ~rev] = 0.0
        J[:, chain.active] = J_path @ chain.S
    return to_frame(J, R, frame)


def to_frame(J: F64, R_root_link: F64, frame: JacobianFrame) -> F64:
    """A world-aligned ``(6, n)`` Jacobian expressed in ``frame`` (a new array for "local")."""
    if frame == "world":
        return J
    if frame != "local":
        raise ValueError(f"frame must be 'world' or 'local', not {frame!r}")
    Rt = R_root_link.T
    out = np.empty_like(J)
    np.matmul(Rt, J[:3], out=out[:3])
    np.matmul(Rt, J[3:], out=out[3:])
    return out
