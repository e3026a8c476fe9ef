"""The links that matter for one target link, as a small compiled model of their own.

IK and Jacobians only need the path from the root to the target link; restricting the model to
it keeps the per-iteration cost independent of the rest of the robot (a humanoid's other limbs).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
from numpy.typing import NDArray

from robomodel.kinematics._compile import PRISMATIC, REVOLUTE, CompiledModel
from robomodel.kinematics.exceptions import KinematicsError
from robomodel.kinematics.fk import SinglePlan, ancestors_closure, make_single_plan

__all__ = ["Chain", "make_chain", "restrict"]

F64 = NDArray[np.float64]


@dataclass(frozen=True, slots=True)
class Chain:
    """The path to one link.

    Attributes:
        model: The path links only (same ``q`` layout as the full model); the target is last.
        plan: Its one-configuration FK plan.
        movable: Indices (in ``model``) of the movable links on the path.
        axis: ``(m, 3)`` unit axes of those links in their own frames.
        revolute: ``(m,)`` True for revolute links, False for prismatic.
        active: Indices into ``q`` of the values that move the target.
        S: ``(m, n_active)``: joint value rates per active ``q`` rate (mimic multipliers).
    """

    model: CompiledModel
    plan: SinglePlan
    movable: NDArray[np.int64]
    axis: F64
    revolute: NDArray[np.bool_]
    active: NDArray[np.int64]
    S: F64


def make_chain(model: CompiledModel, link: int) -> Chain:
    """Restrict ``model`` to the path from the root to ``link`` (1-dof joints only)."""
    sub, path = restrict(model, link)
    movable = [k for k, i in enumerate(path) if model.q_index[i] >= 0]
    for k in movable:
        if sub.kind[k] not in (REVOLUTE, PRISMATIC):
            kind = "floating" if sub.kind[k] == 3 else "planar"
            raise KinematicsError(
                f"the path to '{model.link_names[link]}' goes through the {kind} joint "
                f"'{sub.link_joint[k]}'; Jacobians and IK support revolute, continuous and "
                "prismatic joints only"
            )
    active = sorted({int(sub.q_index[k]) for k in movable})
    column = {q: c for c, q in enumerate(active)}
    S = np.zeros((len(movable), len(active)))
    for row, k in enumerate(movable):
        S[row, column[int(sub.q_index[k])]] += sub.scale[k]
    return Chain(
        model=sub,
        plan=make_single_plan(sub),
        movable=np.array(movable, dtype=np.int64),
        axis=sub.axis[movable],
        revolute=np.array([sub.kind[k] == REVOLUTE for k in movable], dtype=bool),
        active=np.array(active, dtype=np.int64),
        S=S,
    )


def restrict(model: CompiledModel, link: int) -> tuple[CompiledModel, list[int]]:
    """The path from the root to ``link`` as a model of its own (``link`` last), and the
    indices of its links in ``model``. Any joint kind; ``q`` keeps ``model``'s layout."""
    path = ancestors_closure(model, [link])
    new_index = {old: new for new, old in enumerate(path)}
    sub = replace(
        model,
        link_names=tuple(model.link_names[i] for i in path),
        link_index={model.link_names[i]: k for k, i in enumerate(path)},
        parent=tuple(-1 if model.parent[i] < 0 else new_index[model.parent[i]] for i in path),
        link_joint=tuple(model.link_joint[i] for i in path),
        kind=tuple(model.kind[i] for i in path),
        T_parent_joint=model.T_parent_joint[path],
        K=model.K[path],
        Pt=model.Pt[path],
        tilted=tuple(model.tilted[i] for i in path),
        axis=model.axis[path],
        Ka=model.Ka[path],
        q_index=model.q_index[path],
        scale=model.scale[path],
        offset=model.offset[path],
        plane_basis=model.plane_basis[path],
    )
    return sub, path
