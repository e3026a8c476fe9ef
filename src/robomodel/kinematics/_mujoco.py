"""Optional compiled fast path for one configuration: MuJoCo's ``mj_kinematics`` and ``mj_jac``.

One numpy call costs about as much as MuJoCo's whole forward kinematics of a 13-link arm, so a
single configuration is computed by MuJoCo (the ``sim`` extra) when it is installed. The robot
is rebuilt as an ``MjSpec``: one body per link (pose = joint origin), a hinge or slide joint
along the unit axis in the child frame, nominal unit masses (kinematics ignores them). Mimic
joints are separate MuJoCo joints whose value is set from their source, so Jacobian columns are
folded back with the same ``S`` map as the numpy path. The numpy path (:mod:`.fk`,
:mod:`.jacobian`) stays the reference; tests check both agree to 1e-12.

``MjData`` is scratch state, so every thread gets its own.
"""

from __future__ import annotations

import threading
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from robomodel._mujoco_import import import_mujoco
from robomodel.kinematics._compile import FIXED, PRISMATIC, REVOLUTE, CompiledModel

if TYPE_CHECKING:
    from collections.abc import Sequence

__all__ = ["MujocoKinematics", "load_mujoco"]

F64 = NDArray[np.float64]

_UNAVAILABLE = object()
_ONE = np.zeros((4, 4))
_ONE[3, 3] = 1.0
_module: Any = None


def load_mujoco() -> Any:
    """The ``mujoco`` module, or None when it is not installed (imported once)."""
    global _module
    if _module is None:
        try:
            _module = import_mujoco()
        except ImportError:
            _module = _UNAVAILABLE
    return None if _module is _UNAVAILABLE else _module


class MujocoKinematics:
    """FK and Jacobians of a :class:`CompiledModel` with 1-dof and fixed joints, in MuJoCo.

    Raises:
        ValueError: the model has a floating or planar joint (the numpy path handles those).
    """

    def __init__(self, model: CompiledModel, mujoco: Any) -> None:
        if any(k not in (FIXED, REVOLUTE, PRISMATIC) for k in model.kind):
            raise ValueError("only fixed, revolute, continuous and prismatic joints")
        self._mj = mujoco
        self._model = model
        spec = mujoco.MjSpec()
        bodies = [spec.worldbody.add_body(name="l0", mass=1.0, inertia=[1.0, 1.0, 1.0])]
        quat = np.empty(4)
        for i in range(1, model.n_links):
            T = model.T_parent_joint[i]
            mujoco.mju_mat2Quat(quat, np.ascontiguousarray(T[:3, :3]).ravel())
            body = bodies[model.parent[i]].add_body(
                name=f"l{i}", pos=T[:3, 3], quat=quat, mass=1.0, inertia=[1.0, 1.0, 1.0]
            )
            if model.kind[i] != FIXED:
                jtype = mujoco.mjtJoint.mjJNT_HINGE if model.kind[i] == REVOLUTE else None
                body.add_joint(
                    name=f"j{i}",
                    type=jtype or mujoco.mjtJoint.mjJNT_SLIDE,
                    axis=model.axis[i],
                )
            bodies.append(body)
        m = spec.compile()
        self._m = m
        #: MuJoCo body id per link.
        self.body = np.array([m.body(f"l{i}").id for i in range(model.n_links)], dtype=np.int64)
        movable = [i for i in range(model.n_links) if model.kind[i] != FIXED]
        adr = [int(m.jnt_qposadr[m.joint(f"j{i}").id]) for i in movable]
        order = np.argsort(adr)
        movable = [movable[k] for k in order]
        # Velocity columns (MuJoCo dofs) folded into q columns, as in jacobian.chain_columns;
        # the same map gives the joint values: qpos = S @ q + offset (exact: one non-zero
        # product per row).
        S = np.zeros((len(movable), model.n_q))
        for row, i in enumerate(movable):
            S[row, model.q_index[i]] += model.scale[i]
        S.setflags(write=False)
        self.S = S
        self._offset = model.offset[movable].copy()
        self._has_offset = bool(np.any(self._offset != 0.0))
        # Often qpos is q, or its first values (a path that ends before the last joints).
        self._prefix = not self._has_offset and np.array_equal(S, np.eye(len(S), model.n_q))
        self._n_qpos = len(S)
        if not np.array_equal(self.body, np.arange(1, model.n_links + 1)):
            # Never seen (MuJoCo numbers bodies depth-first, as the links are); the per-thread
            # views below rely on it.
            raise ValueError("MuJoCo numbered the bodies in another order than the links")
        self._local = threading.local()
        self._all = np.zeros((model.n_links, 4, 4))
        self._all[:, 3, 3] = 1.0

    @property
    def identity_columns(self) -> bool:
        """True when MuJoCo's dofs are exactly ``q`` (no mimic joint, same order)."""
        return self._prefix and self._n_qpos == self._model.n_q

    def _scratch(self) -> _Scratch:
        try:
            return self._local.scratch  # type: ignore[no-any-return]
        except AttributeError:
            scratch = _Scratch(self._mj.MjData(self._m))
            self._local.scratch = scratch
            return scratch

    def _kinematics(self, q: F64) -> _Scratch:
        s = self._scratch()
        if self._prefix:
            s.qpos[:] = q[: self._n_qpos]
        else:
            np.matmul(self.S, q, out=s.qpos)
            if self._has_offset:
                s.qpos += self._offset
        self._mj.mj_kinematics(self._m, s.data)
        return s

    def fk(self, q: F64, links: Sequence[int] | None = None) -> F64:
        """Poses ``(n, 4, 4)`` of all links (or of ``links``) for one validated ``q``."""
        s = self._kinematics(q)
        out: F64
        if links is None:
            out = self._all.copy()
            out[:, :3, :3] = s.R
            out[:, :3, 3] = s.p
        else:
            idx = list(links)
            out = np.zeros((len(idx), 4, 4))
            out[:, 3, 3] = 1.0
            out[:, :3, :3] = s.R[idx]
            out[:, :3, 3] = s.p[idx]
        out.setflags(write=False)
        return out

    def fk_link(self, q: F64, link: int) -> F64:
        """``T_root_link`` ``(4, 4)`` for one validated ``q``."""
        s = self._kinematics(q)
        out: F64 = _ONE.copy()
        out[:3, :3] = s.R[link]
        out[:3, 3] = s.p[link]
        out.setflags(write=False)
        return out

    def pose_and_jacobian(self, q: F64, link: int, point: F64 | None) -> tuple[F64, F64, F64]:
        """``(R_root_link, p_root_point, J_mj)`` with ``J_mj`` ``(6, n_dof)`` world-aligned.

        ``J_mj``'s columns are MuJoCo's dofs; ``J_mj @ S`` gives ``q`` columns. The arrays are
        this thread's scratch buffers, valid until its next call.
        """
        s = self._kinematics(q)
        mj, m, d = self._mj, self._m, s.data
        mj.mj_comPos(m, d)
        R = s.R[link]
        if point is None:
            p = s.p[link]
            mj.mj_jacBody(m, d, s.Jp, s.Jr, int(self.body[link]))
        else:
            p = R @ point + s.p[link]
            mj.mj_jac(m, d, s.Jp, s.Jr, p, int(self.body[link]))
        return R, p, s.J


class _Scratch:
    """One thread's ``MjData`` and views of it, indexed by link (not by MuJoCo body)."""

    __slots__ = ("J", "Jp", "Jr", "R", "data", "p", "qpos", "xmat", "xpos")

    def __init__(self, data: Any) -> None:
        self.data = data
        self.qpos: F64 = data.qpos
        self.xmat: F64 = data.xmat
        self.xpos: F64 = data.xpos
        # Body k + 1 is link k (checked when the model is built); these are views.
        self.R: F64 = self.xmat[1:].reshape(-1, 3, 3)
        self.p: F64 = self.xpos[1:]
        self.J: F64 = np.empty((6, data.qvel.shape[0]))
        self.Jp: F64 = self.J[:3]
        self.Jr: F64 = self.J[3:]
