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

from robomodel.kinematics._compile import PRISMATIC, REVOLUTE, CompiledModel
from robomodel.kinematics.exceptions import KinematicsError
from robomodel.kinematics.fk import ancestors_closure, fk_batch

__all__ = ["JacobianFrame", "chain_columns", "jacobian_batch"]

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
