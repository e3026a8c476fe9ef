"""Rigid-body dynamics on the compiled model: RNEA, CRBA, gravity, Coriolis, centre of mass.

Spatial vectors are ``[angular; linear]`` (Featherstone's order), expressed in each link's own
frame, which in URDF is also the frame of the joint that carries the link. Inertias are taken
from ``<inertial>`` (a link without one is massless). Results match pinocchio's ``rnea``,
``crba``, ``computeGeneralizedGravity``, ``nonLinearEffects`` and ``centerOfMass`` for models
with revolute, continuous, prismatic and fixed joints (mimic joints are followed: their torque
is folded onto the source joint with the multiplier, which is what ``q`` parametrises).
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

from robomodel.description.model import Robot
from robomodel.kinematics._compile import FIXED, PRISMATIC, REVOLUTE, CompiledModel
from robomodel.kinematics.exceptions import ConfigurationError, KinematicsError

__all__ = ["STANDARD_GRAVITY_M_S2", "Dynamics"]

F64 = NDArray[np.float64]

STANDARD_GRAVITY_M_S2 = 9.81  # pinocchio's Model.gravity981


def _skew(v: F64) -> F64:
    return np.array([[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]])


def _cross(a: F64, b: F64) -> F64:
    """``a × b`` of two 3-vectors: ``np.cross``, which handles stacks of vectors of any axis,
    took two thirds of the inverse dynamics' time on these (38 us a call against 1.5)."""
    a0, a1, a2 = a.tolist()
    b0, b1, b2 = b.tolist()
    return np.array((a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0))


def _rotation(axis: F64, angle_rad: float) -> F64:
    """Rodrigues' formula for a unit ``axis``."""
    c, s = math.cos(angle_rad), math.sin(angle_rad)
    K = _skew(axis)
    result: F64 = np.eye(3) + s * K + (1.0 - c) * (K @ K)
    return result


def _cross_motion(v: F64) -> F64:
    """``v×`` for motion vectors (6x6)."""
    X = np.zeros((6, 6))
    w = _skew(v[:3])
    X[:3, :3] = w
    X[3:, 3:] = w
    X[3:, :3] = _skew(v[3:])
    return X


def _spatial_inertia(robot: Robot, link: str) -> F64:
    """The 6x6 inertia of ``link`` about its frame origin."""
    inertial = robot.link(link).inertial
    out = np.zeros((6, 6))
    if inertial is None:
        return out
    m = inertial.mass_kg
    T = inertial.origin.matrix()
    R, c = T[:3, :3], T[:3, 3]
    Ic = R @ inertial.inertia.matrix() @ R.T
    C = _skew(c)
    out[:3, :3] = Ic + m * (C @ C.T)
    out[:3, 3:] = m * C
    out[3:, :3] = m * C.T
    out[3:, 3:] = m * np.eye(3)
    return out


class Dynamics:
    """Inverse dynamics, mass matrix and gravity of a robot (see the module docstring).

    Args:
        robot: The description (inertias are read from it).
        compiled: Its compiled model (``Kinematics(robot).compiled``).
        gravity_m_s2: Gravity in the root frame; pinocchio's default ``(0, 0, -9.81)``.

    Raises:
        KinematicsError: the model has a floating or planar joint.
    """

    def __init__(
        self,
        robot: Robot,
        compiled: CompiledModel,
        *,
        gravity_m_s2: ArrayLike = (0.0, 0.0, -STANDARD_GRAVITY_M_S2),
    ) -> None:
        self.model = compiled
        for i, kind in enumerate(compiled.kind[1:], start=1):
            if kind not in (FIXED, REVOLUTE, PRISMATIC):
                raise KinematicsError(
                    f"dynamics supports revolute, continuous, prismatic and fixed joints only; "
                    f"joint '{compiled.link_joint[i]}' is floating or planar"
                )
        self.inertia = np.stack([_spatial_inertia(robot, name) for name in compiled.link_names])
        self.masses_kg = np.array(
            [
                0.0 if (inl := robot.link(n).inertial) is None else inl.mass_kg
                for n in compiled.link_names
            ]
        )
        self.coms = np.array(
            [
                np.zeros(3)
                if (inl := robot.link(n).inertial) is None
                else inl.origin.matrix()[:3, 3]
                for n in compiled.link_names
            ]
        )
        n = compiled.n_links
        self.S = np.zeros((n, 6))
        for i in range(1, n):
            if compiled.kind[i] == REVOLUTE:
                self.S[i, :3] = compiled.axis[i]
            elif compiled.kind[i] == PRISMATIC:
                self.S[i, 3:] = compiled.axis[i]
        self.gravity_m_s2 = np.asarray(gravity_m_s2, dtype=np.float64).copy()
        self.gravity_m_s2.setflags(write=False)

    @property
    def n_v(self) -> int:
        return self.model.n_q

    @property
    def total_mass_kg(self) -> float:
        return float(self.masses_kg.sum())

    def _check(self, x: ArrayLike, what: str) -> F64:
        arr = np.asarray(x, dtype=np.float64)
        if arr.shape != (self.n_v,):
            raise ConfigurationError(
                f"{what} has shape {arr.shape}; expected ({self.n_v},) for joints "
                f"{', '.join(self.model.joint_names)}"
            )
        return arr

    def _joint_values(self, q: F64, i: int) -> float:
        m = self.model
        return float(m.scale[i] * q[m.q_index[i]] + m.offset[i])

    def _transforms(self, q: F64) -> tuple[list[F64], list[F64], list[F64]]:
        """Per link: rotation ``R`` (parent <- child), translation ``p`` and pose in the root."""
        m = self.model
        Rs: list[F64] = [np.eye(3)]
        ps: list[F64] = [np.zeros(3)]
        world: list[F64] = [np.eye(4)]
        for i in range(1, m.n_links):
            T = m.T_parent_joint[i].copy()
            kind = m.kind[i]
            if kind == REVOLUTE:
                T[:3, :3] = T[:3, :3] @ _rotation(m.axis[i], self._joint_values(q, i))
            elif kind == PRISMATIC:
                T[:3, 3] = T[:3, 3] + T[:3, :3] @ (m.axis[i] * self._joint_values(q, i))
            Rs.append(T[:3, :3])
            ps.append(T[:3, 3])
            world.append(world[m.parent[i]] @ T)
        return Rs, ps, world

    @staticmethod
    def _motion_to_child(R: F64, p: F64, v: F64) -> F64:
        """Transform a motion vector from the parent's frame to the child's."""
        w = R.T @ v[:3]
        lin = R.T @ (v[3:] - _cross(p, v[:3]))
        return np.concatenate((w, lin))

    @staticmethod
    def _force_to_parent(R: F64, p: F64, f: F64) -> F64:
        """Transform a force vector from the child's frame to the parent's."""
        lin = R @ f[3:]
        ang = R @ f[:3] + _cross(p, lin)
        return np.concatenate((ang, lin))

    def rnea(self, q: ArrayLike, v: ArrayLike, a: ArrayLike, *, gravity: bool = True) -> F64:
        """Joint torques [N·m or N] for positions ``q``, velocities ``v`` and accelerations ``a``.

        Shapes ``(n_q,)`` each. ``gravity=False`` drops the gravity term.
        """
        qa, va, aa = self._check(q, "q"), self._check(v, "v"), self._check(a, "a")
        m = self.model
        Rs, ps, _ = self._transforms(qa)
        n = m.n_links
        vel = [np.zeros(6) for _ in range(n)]
        acc = [np.zeros(6) for _ in range(n)]
        if gravity:
            acc[0][3:] = -self.gravity_m_s2
        force = [np.zeros(6) for _ in range(n)]
        for i in range(1, n):
            par = m.parent[i]
            vi = self._motion_to_child(Rs[i], ps[i], vel[par])
            ai = self._motion_to_child(Rs[i], ps[i], acc[par])
            if m.kind[i] != FIXED:
                k, s = m.q_index[i], m.scale[i]
                vJ = self.S[i] * (s * va[k])
                vi = vi + vJ
                ai = ai + self.S[i] * (s * aa[k]) + _cross_motion(vi) @ vJ
            vel[i], acc[i] = vi, ai
            Iv = self.inertia[i] @ vi
            force[i] = self.inertia[i] @ ai - _cross_motion(vi).T @ Iv
        tau = np.zeros(self.n_v)
        for i in range(n - 1, 0, -1):
            if m.kind[i] != FIXED:
                tau[m.q_index[i]] += m.scale[i] * float(self.S[i] @ force[i])
            par = m.parent[i]
            force[par] = force[par] + self._force_to_parent(Rs[i], ps[i], force[i])
        return tau

    def mass_matrix(self, q: ArrayLike) -> F64:
        """The joint-space inertia matrix ``M(q)``, shape ``(n_q, n_q)``, by the CRBA."""
        qa = self._check(q, "q")
        m = self.model
        Rs, ps, _ = self._transforms(qa)
        n = m.n_links
        Ic = [self.inertia[i].copy() for i in range(n)]
        X: list[F64] = [np.eye(6)]
        for i in range(1, n):  # motion transform parent -> child
            Xi = np.zeros((6, 6))
            RT = Rs[i].T
            Xi[:3, :3] = RT
            Xi[3:, 3:] = RT
            Xi[3:, :3] = -RT @ _skew(ps[i])
            X.append(Xi)
        for i in range(n - 1, 0, -1):
            Ic[m.parent[i]] += X[i].T @ Ic[i] @ X[i]
        M = np.zeros((self.n_v, self.n_v))
        for i in range(1, n):
            if m.kind[i] == FIXED:
                continue
            di, si = m.q_index[i], m.scale[i]
            F = Ic[i] @ (self.S[i] * si)
            M[di, di] += float(self.S[i] @ F) * si
            j = i
            while m.parent[j] > 0:
                F = X[j].T @ F
                j = m.parent[j]
                if m.kind[j] != FIXED:
                    dj, sj = m.q_index[j], m.scale[j]
                    val = float(self.S[j] @ F) * sj
                    M[di, dj] += val
                    M[dj, di] += val
        return M

    def gravity(self, q: ArrayLike) -> F64:
        """The generalised gravity torques ``g(q)``."""
        zero = np.zeros(self.n_v)
        return self.rnea(q, zero, zero)

    def nonlinear_effects(self, q: ArrayLike, v: ArrayLike) -> F64:
        """``C(q, v) v + g(q)`` (pinocchio's ``nonLinearEffects``)."""
        return self.rnea(q, v, np.zeros(self.n_v))

    def coriolis(self, q: ArrayLike, v: ArrayLike) -> F64:
        """The Coriolis and centrifugal torques ``C(q, v) v``."""
        return self.rnea(q, v, np.zeros(self.n_v), gravity=False)

    def forward_dynamics(self, q: ArrayLike, v: ArrayLike, tau: ArrayLike) -> F64:
        """Accelerations ``M(q)⁻¹ (tau − C(q, v) v − g(q))``."""
        rhs = self._check(tau, "tau") - self.nonlinear_effects(q, v)
        result: F64 = np.asarray(np.linalg.solve(self.mass_matrix(q), rhs), dtype=np.float64)
        return result

    def _fixed_to_root(self) -> list[bool]:
        m = self.model
        fixed = [True] * m.n_links
        for i in range(1, m.n_links):
            fixed[i] = fixed[m.parent[i]] and m.kind[i] == FIXED
        return fixed

    def moving_mass_kg(self) -> float:
        """Mass of the links that a joint moves (pinocchio's ``computeTotalMass``)."""
        fixed = self._fixed_to_root()
        return float(sum(mk for mk, f in zip(self.masses_kg, fixed, strict=True) if not f))

    def center_of_mass(self, q: ArrayLike, *, moving_only: bool = False) -> F64:
        """Position [m] of the robot's centre of mass in the root frame.

        ``moving_only`` leaves out the links rigidly attached to the root, as pinocchio's
        ``centerOfMass`` does (it merges them into the fixed "universe" body).
        """
        _, _, world = self._transforms(self._check(q, "q"))
        skip = self._fixed_to_root() if moving_only else [False] * len(world)
        total = float(sum(mk for mk, s in zip(self.masses_kg, skip, strict=True) if not s))
        if total <= 0.0:
            return np.zeros(3)
        acc = np.zeros(3)
        for i, T in enumerate(world):
            if self.masses_kg[i] > 0.0 and not skip[i]:
                acc += self.masses_kg[i] * (T[:3, :3] @ self.coms[i] + T[:3, 3])
        result: F64 = acc / total
        return result
