"""Analytic inverse kinematics of Universal-Robots-type arms (up to 8 solutions).

Nothing is hard-coded: the Denavit-Hartenberg parameters are measured on the model itself.
At the zero configuration the six joint axes (lines in the root frame) must have the UR
structure: axis 1 meets axis 2 at a right angle, axes 2, 3, 4 are parallel, axis 4 meets
axis 5 and axis 5 meets axis 6 at right angles. Standard DH frames are then built on these
lines with UR's twists ``alpha = (pi/2, 0, 0, pi/2, -pi/2, 0)``, giving ``a2, a3, d4, d5`` and
per-joint signs and angle offsets (``theta_dh = sign * q + offset``), plus the constant
transforms from the root to DH frame 0 and from DH frame 6 to the target link. The model is
accepted only if this DH chain reproduces its FK on random configurations.

The solution itself is geometric (as in Hawkins, "Analytic inverse kinematics for the
Universal Robots UR-5/UR-10 arms", 2013, rewritten with frame 6 on the wrist centre):
``theta1`` from the wrist centre's offset ``d4`` (2 branches), ``theta5`` from the tool axis
(2), ``theta6`` from the tool's x/y axes, ``theta2``/``theta3`` from a planar 2R problem (2),
``theta4`` from the remaining in-plane angle. Every candidate is checked by FK.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from robomodel.kinematics._chain import Chain, make_chain
from robomodel.kinematics._compile import REVOLUTE, CompiledModel
from robomodel.kinematics.exceptions import KinematicsError
from robomodel.kinematics.fk import fk_batch, fk_single, make_single_plan
from robomodel.kinematics.se3 import inverse_transform, log_rotation

__all__ = ["NotAnalyticError", "URGeometry", "solve_ur", "ur_geometry"]

F64 = NDArray[np.float64]
_TOL = 1e-9


class NotAnalyticError(KinematicsError):
    """No analytic solver applies to this chain."""


@dataclass(frozen=True, slots=True)
class URGeometry:
    """UR-type parameters measured on a model (lengths [m], angles [rad]).

    ``a2``, ``a3`` are the upper arm and forearm lengths, ``d4`` the shoulder-to-wrist offset
    along the parallel axes, ``d5`` the wrist 1-2 offset (UR's DH table, with ``a`` taken
    positive). ``d1`` (shoulder height above the root) and ``d6`` (wrist centre to the target
    link along axis 6) are informative: the solver keeps them in ``T_root_base`` and
    ``T_tool_link``.
    """

    a2: float
    a3: float
    d4: float
    d5: float
    d1: float
    d6: float
    sign: F64
    offset: F64
    q_index: NDArray[np.int64]
    T_root_base: F64
    T_tool_link: F64


def _closest_points(p1: F64, u1: F64, p2: F64, u2: F64) -> tuple[F64, F64]:
    """Closest points of two non-parallel lines."""
    w = p1 - p2
    b = float(u1 @ u2)
    d, e = float(u1 @ w), float(u2 @ w)
    den = 1.0 - b * b
    s = (b * e - d) / den
    t = (e - b * d) / den
    return p1 + s * u1, p2 + t * u2


def _meet_at_right_angle(p1: F64, u1: F64, p2: F64, u2: F64, what: str) -> F64:
    if abs(float(u1 @ u2)) > _TOL:
        raise NotAnalyticError(f"{what}: the axes are not perpendicular")
    a, b = _closest_points(p1, u1, p2, u2)
    if np.linalg.norm(a - b) > 1e-7:
        raise NotAnalyticError(f"{what}: the axes do not intersect")
    result: F64 = 0.5 * (a + b)
    return result


def _angle_about(x_from: F64, x_to: F64, z: F64) -> float:
    return math.atan2(float(np.cross(x_from, x_to) @ z), float(x_from @ x_to))


def _unit(v: F64) -> F64:
    result: F64 = v / np.linalg.norm(v)
    return result


def _check_ur_chain(model: CompiledModel, link: int, chain: Chain) -> None:
    """Refuse chains the UR solver cannot represent: its ``q`` has six independent revolute
    values, one per joint, with no mimic scale or offset."""
    sub = chain.model
    movable = chain.movable.tolist()
    if len(movable) != 6 or not all(sub.kind[k] == REVOLUTE for k in movable):
        raise NotAnalyticError(
            f"the chain to '{model.link_names[link]}' has {len(movable)} movable joints; "
            "the UR solver needs exactly 6 revolute ones"
        )
    if np.any(sub.scale[movable] != 1.0) or np.any(sub.offset[movable] != 0.0):
        raise NotAnalyticError("the UR solver does not handle mimic joints on the chain")
    if len(set(sub.q_index[movable].tolist())) != 6:
        raise NotAnalyticError("the chain's joints are not independent")


def _dh_z_axes(u_root: list[F64]) -> tuple[list[F64], list[float]]:
    """The DH z axes (root frame) and the sign of each joint's value along them.

    UR's twists are ``alpha = 0`` between joints 2, 3 and 4, so their z axes share one
    direction; a URDF axis pointing the other way turns with sign -1.
    """
    z = [u_root[0], u_root[1]]
    sign = [1.0, 1.0]
    for k in (2, 3):  # alpha = 0: same direction as the previous z
        if abs(abs(float(u_root[k] @ z[1])) - 1.0) > _TOL:
            raise NotAnalyticError(f"axes 2 and {k + 1} are not parallel")
        sign.append(1.0 if float(u_root[k] @ z[1]) > 0 else -1.0)
        z.append(sign[-1] * u_root[k])
    z.extend([u_root[4], u_root[5]])
    sign.extend([1.0, 1.0])
    return z, sign


@dataclass(frozen=True, slots=True)
class _DHFrames:
    """Origins ``O`` and x axes of DH frames 1 to 5, in the root frame, and the arm lengths.

    Attributes:
        O1, O3, O4, O5: Frame origins [m] (frame 2's is only a step towards frame 3's).
        x1, x2, x3, x4, x5: Unit x axes, each the common normal of its z and the next.
        a2, a3: Upper arm and forearm lengths [m].
    """

    O1: F64
    O3: F64
    O4: F64
    O5: F64
    x1: F64
    x2: F64
    x3: F64
    x4: F64
    x5: F64
    a2: float
    a3: float


def _dh_frames(u_root: list[F64], c_root: list[F64], z: list[F64]) -> _DHFrames:
    """Build the DH frames on the joint axes (lines through ``c_root`` along ``u_root``),
    checking that they meet as UR's do."""
    O1 = _meet_at_right_angle(c_root[0], u_root[0], c_root[1], u_root[1], "joints 1 and 2")
    # Parallel axes 2, 3, 4: common normals through O1 (d2 = d3 = 0).
    w2 = c_root[2] - O1 - float((c_root[2] - O1) @ z[1]) * z[1]
    a2 = float(np.linalg.norm(w2))
    O2 = O1 + w2
    w3 = c_root[3] - O2 - float((c_root[3] - O2) @ z[1]) * z[1]
    a3 = float(np.linalg.norm(w3))
    if a2 < 1e-6 or a3 < 1e-6:
        raise NotAnalyticError("the upper arm or forearm has zero length")
    return _DHFrames(
        O1=O1,
        O3=O2 + w3,
        O4=_meet_at_right_angle(c_root[3], u_root[3], c_root[4], u_root[4], "joints 4 and 5"),
        O5=_meet_at_right_angle(c_root[4], u_root[4], c_root[5], u_root[5], "joints 5 and 6"),
        x1=_unit(np.cross(z[0], z[1])),
        x2=w2 / a2,
        x3=w3 / a3,
        x4=_unit(np.cross(z[3], z[4])),
        x5=_unit(np.cross(z[5], z[4])),
        a2=a2,
        a3=a3,
    )


def _frame(x_root: F64, z_root: F64, origin_root: F64) -> F64:
    """``T_root_frame`` of the frame with these x and z axes and origin."""
    T_root_frame = np.eye(4)
    T_root_frame[:3, :3] = np.column_stack([x_root, np.cross(z_root, x_root), z_root])
    T_root_frame[:3, 3] = origin_root
    return T_root_frame


def ur_geometry(model: CompiledModel, link: int) -> URGeometry:
    """Measure the UR parameters of the chain to ``link`` (``NotAnalyticError`` if not UR)."""
    chain = make_chain(model, link)
    _check_ur_chain(model, link, chain)
    sub = chain.model
    movable = chain.movable.tolist()
    Ts0 = fk_single(sub, make_single_plan(sub), np.zeros(sub.n_q))
    u = [_unit(Ts0[k, :3, :3] @ sub.axis[k]) for k in movable]
    c = [Ts0[k, :3, 3] for k in movable]
    z, sign = _dh_z_axes(u)
    f = _dh_frames(u, c, z)
    offset = [
        0.0,
        _angle_about(f.x1, f.x2, z[1]),
        _angle_about(f.x2, f.x3, z[2]),
        _angle_about(f.x3, f.x4, z[3]),
        _angle_about(f.x4, f.x5, z[4]),
        0.0,
    ]
    T_root_tool = _frame(f.x5, z[5], f.O5)
    geometry = URGeometry(
        a2=f.a2,
        a3=f.a3,
        d4=float((f.O4 - f.O3) @ z[3]),
        d5=float((f.O5 - f.O4) @ z[4]),
        d1=float(f.O1 @ z[0]),
        d6=float(inverse_transform(T_root_tool)[2] @ np.append(Ts0[-1, :3, 3], 1.0)),
        sign=np.array(sign),
        offset=np.array(offset),
        q_index=sub.q_index[movable].astype(np.int64),
        T_root_base=_frame(f.x1, z[0], f.O1),
        T_tool_link=inverse_transform(T_root_tool) @ Ts0[-1],
    )
    _verify(model, link, geometry)
    return geometry


def _dh_fk(g: URGeometry, theta: F64) -> F64:
    """``T_base_tool`` of the measured DH chain."""
    d = (0.0, 0.0, 0.0, g.d4, g.d5, 0.0)
    a = (0.0, g.a2, g.a3, 0.0, 0.0, 0.0)
    alpha = (math.pi / 2, 0.0, 0.0, math.pi / 2, -math.pi / 2, 0.0)
    T = np.eye(4)
    for k in range(6):
        ct, st = math.cos(theta[k]), math.sin(theta[k])
        ca, sa = math.cos(alpha[k]), math.sin(alpha[k])
        T = T @ np.array(
            [
                [ct, -st * ca, st * sa, a[k] * ct],
                [st, ct * ca, -ct * sa, a[k] * st],
                [0.0, sa, ca, d[k]],
                [0.0, 0.0, 0.0, 1.0],
            ]
        )
    return T


def _verify(model: CompiledModel, link: int, g: URGeometry) -> None:
    rng = np.random.default_rng(0)
    qs = rng.uniform(-math.pi, math.pi, size=(8, model.n_q))
    Ts = fk_batch(model, qs, [link])[:, 0]
    for q, T in zip(qs, Ts, strict=True):
        theta = g.sign * q[g.q_index] + g.offset
        T_dh = g.T_root_base @ _dh_fk(g, theta) @ g.T_tool_link
        if not np.allclose(T_dh, T, atol=1e-9):
            raise NotAnalyticError("the chain does not follow UR kinematics")


def _wrap(angle: float) -> float:
    return (angle + math.pi) % (2.0 * math.pi) - math.pi


def solve_ur(
    model: CompiledModel, link: int, g: URGeometry, T_root_target: F64, *, tol: float = 1e-6
) -> F64:
    """All solutions ``(n, n_q)`` (other joints 0, or their lower limit if 0 is outside)."""
    T = inverse_transform(g.T_root_base) @ T_root_target @ inverse_transform(g.T_tool_link)
    R, p = T[:3, :3], T[:3, 3]
    z5 = R[:, 2]
    candidates: list[list[float]] = []
    r = math.hypot(p[0], p[1])
    if r < abs(g.d4) or r == 0.0:
        return np.zeros((0, model.n_q))
    phi = math.atan2(p[1], p[0])
    base = math.asin(g.d4 / r)
    for t1 in (phi + base, phi + math.pi - base):
        x1 = np.array([math.cos(t1), math.sin(t1), 0.0])
        z1 = np.array([math.sin(t1), -math.cos(t1), 0.0])
        y1 = np.cross(z1, x1)
        c5 = max(-1.0, min(1.0, float(z1 @ z5)))
        for t5 in (math.acos(c5), -math.acos(c5)):
            s5 = math.sin(t5)
            if abs(s5) < 1e-12:
                continue  # wrist singularity: theta4 and theta6 are not separable
            z4 = np.cross(z1, z5) / s5
            x4 = (c5 * z1 - z5) / s5
            t6 = math.atan2(-float(z4 @ R[:, 0]), -float(z4 @ R[:, 1]))
            P = p - g.d5 * z4 - g.d4 * z1
            px, py = float(P @ x1), float(P @ y1)
            c3 = (px * px + py * py - g.a2 * g.a2 - g.a3 * g.a3) / (2.0 * g.a2 * g.a3)
            if abs(c3) > 1.0 + 1e-12:
                continue
            c3 = max(-1.0, min(1.0, c3))
            for t3 in (math.acos(c3), -math.acos(c3)):
                t2 = math.atan2(py, px) - math.atan2(
                    g.a3 * math.sin(t3), g.a2 + g.a3 * math.cos(t3)
                )
                t4 = math.atan2(float(x4 @ y1), float(x4 @ x1)) - t2 - t3
                candidates.append([t1, t2, t3, t4, t5, t6])
    return _to_model(model, link, g, candidates, T_root_target, tol)


def _to_model(
    model: CompiledModel,
    link: int,
    g: URGeometry,
    candidates: list[list[float]],
    T_root_target: F64,
    tol: float,
) -> F64:
    rest = np.where((model.lower <= 0.0) & (model.upper >= 0.0), 0.0, model.lower)
    rest = np.where(np.isfinite(rest), rest, 0.0)
    solutions: list[F64] = []
    for theta in candidates:
        q = rest.copy()
        ok = True
        for k in range(6):
            value = _wrap(g.sign[k] * (theta[k] - g.offset[k]))
            i = int(g.q_index[k])
            # The representative nearest 0 among value + 2 pi n that fits the limits.
            choices = [value + 2.0 * math.pi * n for n in (0, -1, 1, -2, 2)]
            fits = [v for v in choices if model.lower[i] - 1e-12 <= v <= model.upper[i] + 1e-12]
            if not fits:
                ok = False
                break
            q[i] = min(fits, key=abs)
        if not ok:
            continue
        T = fk_batch(model, q[None], [link])[0, 0]
        if np.linalg.norm(T[:3, 3] - T_root_target[:3, 3]) > tol:
            continue
        if np.linalg.norm(log_rotation(T_root_target[:3, :3] @ T[:3, :3].T)) > tol:
            continue
        if any(np.allclose(q, s, atol=1e-9) for s in solutions):
            continue
        solutions.append(q)
    out = np.array(solutions) if solutions else np.zeros((0, model.n_q))
    out.setflags(write=False)
    return out
