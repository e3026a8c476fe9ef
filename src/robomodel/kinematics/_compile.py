"""Compiling a :class:`~robomodel.description.Robot` into flat tables for kinematics.

Links are ordered depth-first from the root (children in urdfdom's order, i.e. by joint name),
so every link comes after its parent. The actuated joints are the movable, non-mimic joints
in that same order, which is also pinocchio's order.

Every revolute (and continuous) joint is rewritten so that it turns about z: with ``P`` a
constant rotation taking z to the joint's unit axis, ``T_origin @ R_axis(t) ==
(T_origin @ P) @ Rz(t) @ P.T``. ``K = T_origin @ P`` is precomputed, and ``P.T`` is only
applied when the axis is not already z (most robots give z).
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from robomodel.description.model import Joint, JointType, Robot, UnknownNameError
from robomodel.errors import close_matches
from robomodel.kinematics.exceptions import (
    KinematicsError,
    KinematicsWarning,
    MimicCycleError,
    ZeroAxisError,
)
from robomodel.kinematics.se3 import rotation_z_to

__all__ = ["FIXED", "FLOATING", "PLANAR", "PRISMATIC", "REVOLUTE", "CompiledModel", "compile_robot"]

F64 = NDArray[np.float64]
I64 = NDArray[np.int64]

FIXED, REVOLUTE, PRISMATIC, FLOATING, PLANAR = 0, 1, 2, 3, 4

_KIND = {
    JointType.FIXED: FIXED,
    JointType.REVOLUTE: REVOLUTE,
    JointType.CONTINUOUS: REVOLUTE,
    JointType.PRISMATIC: PRISMATIC,
    JointType.FLOATING: FLOATING,
    JointType.PLANAR: PLANAR,
}
_Q_SIZE = {FIXED: 0, REVOLUTE: 1, PRISMATIC: 1, FLOATING: 7, PLANAR: 3}


def _readonly(a: F64) -> F64:
    a.setflags(write=False)
    return a


def _readonly_int(a: I64) -> I64:
    a.setflags(write=False)
    return a


@dataclass(frozen=True, slots=True)
class CompiledModel:
    """Flat per-link tables (index 0 is the root link). Arrays are read-only.

    Attributes:
        link_names: Links, depth-first from the root.
        parent: Parent link index per link (-1 for the root).
        link_joint: Name of the joint whose child each link is (``None`` for the root).
        kind: Joint kind per link (``FIXED``, ``REVOLUTE``, ...).
        T_parent_joint: ``(n_links, 4, 4)`` joint origins.
        K: ``(n_links, 4, 4)``: ``T_parent_joint @ P`` (P turns z into the joint axis).
        Pt: ``(n_links, 4, 4)``: ``P.T`` as a transform.
        tilted: Per link, True when ``P`` is not the identity.
        axis: ``(n_links, 3)`` unit joint axes (zero for fixed joints).
        Ka: ``(n_links, 3)``: prismatic axis expressed in the parent frame (``R_origin @ axis``).
        q_index: Index into ``q`` of each link's joint value, or of the first of its values
            (floating, planar), or of the mimicked joint's value; -1 for fixed joints.
        scale, offset: ``value = scale * q[q_index] + offset`` (1 and 0 unless mimic).
        joint_names: Actuated joints in ``q`` order.
        q_start, q_size: Where each actuated joint's values sit in ``q``.
        lower, upper: ``(n_q,)`` position limits [rad or m]; infinite where unlimited.
        plane_basis: ``(n_links, 2, 3)`` in-plane unit vectors of planar joints.
    """

    link_names: tuple[str, ...]
    link_index: Mapping[str, int]
    parent: tuple[int, ...]
    link_joint: tuple[str | None, ...]
    kind: tuple[int, ...]
    T_parent_joint: F64
    K: F64
    Pt: F64
    tilted: tuple[bool, ...]
    axis: F64
    Ka: F64
    q_index: I64
    scale: F64
    offset: F64
    joint_names: tuple[str, ...]
    joint_index: Mapping[str, int]
    q_start: tuple[int, ...]
    q_size: tuple[int, ...]
    n_q: int
    lower: F64
    upper: F64
    plane_basis: F64
    mimic: Mapping[str, tuple[str, float, float]]

    @property
    def n_links(self) -> int:
        return len(self.link_names)

    def link(self, name: str) -> int:
        """Index of link ``name`` (``UnknownNameError`` lists the valid names)."""
        try:
            return self.link_index[name]
        except KeyError:
            raise UnknownNameError("link", name, self.link_names) from None


def _unit_axis(joint: Joint) -> F64:
    a = np.asarray(joint.axis, dtype=np.float64)
    norm = float(np.linalg.norm(a))
    if norm == 0.0 or not math.isfinite(norm):
        raise ZeroAxisError(joint.name)
    result: F64 = a / norm
    return result


def _resolve_mimic(
    name: str, joints: Mapping[str, Joint], actuated: set[str]
) -> tuple[str, float, float]:
    """Follow a mimic chain to an actuated joint: ``value = f * q[root] + o``."""
    path: list[str] = []
    factor, offset = 1.0, 0.0
    current = name
    while current not in actuated:
        if current in path:
            raise MimicCycleError(path[path.index(current) :])
        path.append(current)
        joint = joints[current]
        if joint.mimic is None:  # a movable joint is either actuated or a mimic
            raise KinematicsError(f"joint '{current}' is neither actuated nor a mimic joint")
        source = joint.mimic.joint
        if source not in joints:
            raise KinematicsError(
                f"joint '{current}' mimics '{source}', which does not exist; "
                f"joints are: {', '.join(joints)}"
            )
        src = joints[source]
        if _KIND[src.type] not in (REVOLUTE, PRISMATIC):
            raise KinematicsError(
                f"joint '{current}' mimics '{source}', a {src.type.value} joint; "
                "only revolute, continuous and prismatic joints can be mimicked"
            )
        m, o = joint.mimic.multiplier_or_default, joint.mimic.offset_or_default
        # value(current) = m * value(source) + o, composed outside-in.
        offset = offset + factor * o
        factor = factor * m
        current = source
    return current, factor, offset


def _is_mimic(joint: Joint, joints_by_name: Mapping[str, Joint]) -> bool:
    """Whether ``joint`` follows another joint rather than taking its own value in ``q``.

    A mimic of a joint that does not exist is warned about and kept independent.
    """
    if joint.mimic is None or _KIND[joint.type] not in (REVOLUTE, PRISMATIC):
        return False
    if joint.mimic.joint in joints_by_name:
        return True
    # pinocchio (without mimic=True) and robot_state_publisher both leave such a joint
    # independent; refusing the whole robot would be worse.
    hint = close_matches(joint.mimic.joint, joints_by_name)
    warnings.warn(
        f"joint '{joint.name}' mimics '{joint.mimic.joint}', which does not exist"
        + (f" (did you mean {', '.join(repr(h) for h in hint)}?)" if hint else "")
        + "; it is treated as an independent joint",
        KinematicsWarning,
        stacklevel=3,
    )
    return False


def _actuated_joints(
    link_joints: Sequence[Joint | None], joints_by_name: Mapping[str, Joint]
) -> tuple[Joint, ...]:
    """The joints that take values in ``q``: movable and not mimics, in link order."""
    actuated: list[Joint] = []
    # A loop rather than a comprehension: the warning's stacklevel counts frames.
    for joint in link_joints:
        if joint is not None and joint.type.is_movable and not _is_mimic(joint, joints_by_name):
            actuated.append(joint)
    return tuple(actuated)


@dataclass(frozen=True, slots=True)
class _QLayout:
    """Where each actuated joint's values sit in ``q``, and the position limits of ``q``.

    Attributes:
        joints: Actuated joints in ``q`` order.
        q_start, q_size: Per actuated joint, its first index in ``q`` and its number of values.
        lower, upper: Per value of ``q``, its limits [rad or m]; infinite where unlimited.
    """

    joints: tuple[Joint, ...]
    q_start: tuple[int, ...]
    q_size: tuple[int, ...]
    lower: tuple[float, ...]
    upper: tuple[float, ...]

    def start_of(self) -> dict[str, int]:
        """First index in ``q`` of each actuated joint, by name."""
        return {j.name: s for j, s in zip(self.joints, self.q_start, strict=True)}


def _q_layout(actuated: tuple[Joint, ...]) -> _QLayout:
    """Lay the actuated joints' values out in ``q``, with their limits."""
    q_start: list[int] = []
    q_size: list[int] = []
    lower: list[float] = []
    upper: list[float] = []
    for joint in actuated:
        size = _Q_SIZE[_KIND[joint.type]]
        q_start.append(len(lower))
        q_size.append(size)
        if joint.type in (JointType.REVOLUTE, JointType.PRISMATIC):
            limit = joint.limit
            lower.append(-math.inf if limit is None else limit.lower_or_default)
            upper.append(math.inf if limit is None else limit.upper_or_default)
        else:  # continuous, floating and planar values are unlimited
            lower.extend([-math.inf] * size)
            upper.extend([math.inf] * size)
    return _QLayout(actuated, tuple(q_start), tuple(q_size), tuple(lower), tuple(upper))


@dataclass(frozen=True, slots=True)
class _LinkTables:
    """The per-link arrays of :class:`CompiledModel` while they are filled, joint by joint.

    The binding is frozen; the arrays are written in place, then made read-only.
    """

    T_parent_joint: F64
    K: F64
    Pt: F64
    tilted: list[bool]
    axis: F64
    Ka: F64
    q_index: I64
    scale: F64
    offset: F64
    plane_basis: F64

    @classmethod
    def identity(cls, n_links: int) -> _LinkTables:
        """Tables for ``n_links`` fixed identity joints (what the root link keeps)."""
        return cls(
            T_parent_joint=np.tile(np.eye(4), (n_links, 1, 1)),
            K=np.tile(np.eye(4), (n_links, 1, 1)),
            Pt=np.tile(np.eye(4), (n_links, 1, 1)),
            tilted=[False] * n_links,
            axis=np.zeros((n_links, 3)),
            Ka=np.zeros((n_links, 3)),
            q_index=np.full(n_links, -1, dtype=np.int64),
            scale=np.ones(n_links),
            offset=np.zeros(n_links),
            plane_basis=np.zeros((n_links, 2, 3)),
        )

    def set_axis(self, i: int, joint: Joint, kind: int) -> None:
        """Fill link ``i``'s axis tables for movable ``joint``, whose origin is already set.

        A revolute joint about a tilted axis is turned to rotate about z (module docstring),
        so that FK only ever builds ``Rz``.
        """
        a = _unit_axis(joint) if kind != FLOATING else np.array([0.0, 0.0, 1.0])
        self.axis[i] = a
        P = rotation_z_to(a)
        T_o = self.T_parent_joint[i]
        if kind == REVOLUTE and not np.array_equal(P, np.eye(3)):
            self.tilted[i] = True
            self.K[i, :3, :3] = T_o[:3, :3] @ P
            self.Pt[i, :3, :3] = P.T
        self.Ka[i] = T_o[:3, :3] @ a
        self.plane_basis[i, 0] = P[:, 0]
        self.plane_basis[i, 1] = P[:, 1]

    def set_source(self, i: int, q_index: int, scale: float = 1.0, offset: float = 0.0) -> None:
        """Link ``i``'s joint value is ``scale * q[q_index] + offset``."""
        self.q_index[i] = q_index
        self.scale[i] = scale
        self.offset[i] = offset


def compile_robot(robot: Robot) -> CompiledModel:
    """Compile ``robot`` (raises ``TreeError``, ``ZeroAxisError``, ``MimicCycleError``)."""
    tree = robot.tree()
    links = tree.links_depth_first()
    index = {name: i for i, name in enumerate(links)}
    n = len(links)
    link_joints: list[Joint | None] = [None, *(tree.parent_joint[link] for link in links[1:])]
    joints_by_name = {j.name: j for j in link_joints if j is not None}
    layout = _q_layout(_actuated_joints(link_joints, joints_by_name))
    actuated_names = {j.name for j in layout.joints}
    start_of = layout.start_of()
    parent = [-1] * n
    kind_of = [FIXED] * n
    tables = _LinkTables.identity(n)
    mimic: dict[str, tuple[str, float, float]] = {}
    for i, joint in enumerate(link_joints):
        if joint is None:
            continue
        parent[i] = index[joint.parent]
        kind_of[i] = kind = _KIND[joint.type]
        tables.T_parent_joint[i] = tables.K[i] = joint.origin.matrix()
        if kind == FIXED:
            continue
        tables.set_axis(i, joint, kind)
        if joint.name in actuated_names:
            tables.set_source(i, start_of[joint.name])
        else:
            root, factor, offset = _resolve_mimic(joint.name, joints_by_name, actuated_names)
            mimic[joint.name] = (root, factor, offset)
            tables.set_source(i, start_of[root], factor, offset)
    names = tuple(j.name for j in layout.joints)
    return CompiledModel(
        link_names=links,
        link_index=index,
        parent=tuple(parent),
        link_joint=tuple(None if j is None else j.name for j in link_joints),
        kind=tuple(kind_of),
        T_parent_joint=_readonly(tables.T_parent_joint),
        K=_readonly(tables.K),
        Pt=_readonly(tables.Pt),
        tilted=tuple(tables.tilted),
        axis=_readonly(tables.axis),
        Ka=_readonly(tables.Ka),
        q_index=_readonly_int(tables.q_index),
        scale=_readonly(tables.scale),
        offset=_readonly(tables.offset),
        joint_names=names,
        joint_index={name: i for i, name in enumerate(names)},
        q_start=layout.q_start,
        q_size=layout.q_size,
        n_q=len(layout.lower),
        lower=_readonly(np.array(layout.lower, dtype=np.float64)),
        upper=_readonly(np.array(layout.upper, dtype=np.float64)),
        plane_basis=_readonly(tables.plane_basis),
        mimic=mimic,
    )
