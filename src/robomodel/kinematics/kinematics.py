"""The :class:`Kinematics` object: a robot compiled for FK, Jacobians and IK."""

from __future__ import annotations

import math
import os
from collections.abc import Sequence
from typing import TYPE_CHECKING, Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from robomodel.description.model import Robot
from robomodel.kinematics._chain import Chain, make_chain, restrict
from robomodel.kinematics._checks import check_limits, check_q, link_indices
from robomodel.kinematics._compile import CompiledModel, compile_robot
from robomodel.kinematics._config_space import ConfigurationSpace
from robomodel.kinematics._ik_options import IKOptionOverrides, IKOptions
from robomodel.kinematics._mujoco import MujocoKinematics, load_mujoco
from robomodel.kinematics.exceptions import KinematicsError
from robomodel.kinematics.fk import SinglePlan, fk_batch, fk_single, make_single_plan
from robomodel.kinematics.jacobian import JacobianFrame, jacobian_batch, jacobian_single, to_frame

if TYPE_CHECKING:
    from typing_extensions import Unpack

    from robomodel.kinematics.dynamics import Dynamics
    from robomodel.kinematics.ik import IKBatchResult, IKResult, Solver
    from robomodel.kinematics.ur import NotAnalyticError, URGeometry

__all__ = ["Backend", "Kinematics"]

_ORIGIN = (0.0, 0.0, 0.0)
F64 = NDArray[np.float64]
Backend = Literal["auto", "numpy", "mujoco"]


class Kinematics(ConfigurationSpace):
    """Forward kinematics, Jacobians and inverse kinematics of a robot model.

    ``q`` holds the actuated joints in :attr:`joint_names` order: depth-first from the root
    link, children in urdfdom's order (by joint name); this is also pinocchio's order. Mimic
    joints are not in ``q``: their value is ``multiplier * source + offset``, chains resolved.
    Revolute, continuous and prismatic joints take one value [rad or m]; a floating joint
    takes 7 (``x y z qx qy qz qw``, the quaternion normalised); a planar joint takes 3 (``x y``
    along the plane's basis vectors, then the angle about the axis). The plane basis is the
    image of the x and y axes under the smallest rotation taking z onto the joint axis (so it
    is x and y for a z axis, as in pinocchio).

    One configuration (``q`` of shape ``(n_q,)``) is computed by MuJoCo's compiled
    kinematics when the ``sim`` extra is installed (``backend="auto"``); batches, and models
    with floating or planar joints, always use the numpy implementation. Both give the same
    numbers to about 1e-15 m (the tests check 1e-12).

    Args:
        robot: The model; its joint axes are normalised as KDL does.
        backend: ``"auto"`` (MuJoCo for one configuration when it can be imported, imported on
            first use), ``"numpy"`` (no compiled code: the reference, and the cheapest start-up
            for a process that computes a handful of poses) or ``"mujoco"`` (an error if it
            cannot be used).

    Raises:
        TreeError: the joints do not form a tree.
        ZeroAxisError: a movable joint has a zero axis.
        MimicCycleError: mimic joints follow each other in a loop.
        KinematicsError: ``backend="mujoco"`` and MuJoCo is missing or cannot model a joint.
    """

    def __init__(self, robot: Robot, *, backend: Backend = "auto") -> None:
        if backend not in ("auto", "numpy", "mujoco"):
            raise ValueError(f"backend must be 'auto', 'numpy' or 'mujoco', not {backend!r}")
        self._robot = robot
        self._model = compile_robot(robot)
        self._plan = make_single_plan(self._model)
        self._backend: Backend = backend
        self._fast: MujocoKinematics | None = None
        self._fast_ready = False
        self._chains: dict[int, Chain] = {}
        self._paths: dict[int, tuple[CompiledModel, SinglePlan]] = {}
        if backend == "mujoco":
            self._fast_path()
        self._solvers: dict[tuple[str, bool], Solver] = {}
        self._analytic: dict[str, URGeometry | NotAnalyticError] = {}
        self._dynamics: Dynamics | None = None

    @classmethod
    def load(cls, path_or_text: str | os.PathLike[str], **options: object) -> Kinematics:
        """Load a description with :func:`robomodel.load` (same options) and compile it."""
        from robomodel.loading import load

        return cls(load(path_or_text, **options))  # type: ignore[arg-type]

    @property
    def robot(self) -> Robot:
        return self._robot

    @property
    def backend(self) -> Literal["numpy", "mujoco"]:
        """What computes one configuration (``"auto"`` resolved, which may import MuJoCo)."""
        return "numpy" if self._fast_path() is None else "mujoco"

    def _fast_path(self) -> MujocoKinematics | None:
        """The MuJoCo model for one configuration, built on first use (None: numpy)."""
        fast = self._fast
        if not self._fast_ready:
            if self._backend != "numpy" and self._model.n_q > 0:
                mujoco = load_mujoco()
                try:
                    fast = None if mujoco is None else MujocoKinematics(self._model, mujoco)
                except ValueError:
                    fast = None
            if fast is None and self._backend == "mujoco":
                raise KinematicsError(
                    "backend='mujoco' needs the mujoco package (pip install 'robomodel[sim]') "
                    "and a model with only fixed, revolute, continuous and prismatic joints"
                )
            self._fast, self._fast_ready = fast, True
        return fast

    def _path(self, link: int) -> tuple[CompiledModel, SinglePlan]:
        """The path to ``link`` (any joint kinds) and its FK plan, built once per link."""
        found = self._paths.get(link)
        if found is None:
            sub, _ = restrict(self._model, link)
            found = self._paths[link] = (sub, make_single_plan(sub))
        return found

    def _chain(self, link: int) -> Chain:
        """The path to ``link`` as its own small model (built once per link)."""
        chain = self._chains.get(link)
        if chain is None:
            chain = self._chains[link] = make_chain(self._model, link)
        return chain

    @property
    def compiled(self) -> CompiledModel:
        """The flat tables the algorithms use (read-only)."""
        return self._model

    def dynamics(self) -> Dynamics:
        """Rigid-body dynamics (RNEA, CRBA, gravity, CoM) of this model; built once."""
        if self._dynamics is None:
            from robomodel.kinematics.dynamics import Dynamics

            self._dynamics = Dynamics(self._robot, self._model)
        return self._dynamics

    def fk(
        self,
        q: ArrayLike,
        *,
        links: Sequence[str] | None = None,
        check_limits: bool = False,
    ) -> F64:
        """Poses of links in the root frame: ``Ts_root_link``.

        Args:
            q: Shape ``(n_q,)`` or ``(*batch, n_q)``.
            links: Names of the links wanted (default: all, in :attr:`link_names` order).
            check_limits: Raise :class:`ConfigurationError` if a value is outside its limits
                (by default values outside the limits are accepted silently).

        Returns:
            Read-only float64 array ``(*batch, n_links, 4, 4)``. A batched result is a
            transposed view of a batch-last buffer (not C-contiguous).
        """
        arr = check_q(self._model, q)
        if check_limits:
            self._check_limits(arr)
        idx = None if links is None else link_indices(self._model, links)
        if arr.ndim == 1:
            fast = self._fast if self._fast_ready else self._fast_path()
            if fast is not None:
                return fast.fk(arr, idx)
            Ts = fk_single(self._model, self._plan, arr)
            if idx is not None:
                Ts = Ts[idx]
                Ts.setflags(write=False)
            return Ts
        batch = arr.shape[:-1]
        flat = arr.reshape(math.prod(batch), self.n_q)
        out = fk_batch(self._model, flat, idx)
        return out.reshape(*batch, *out.shape[1:])

    def _check_limits(self, arr: F64) -> None:
        check_limits(self._model, arr)

    def fk_link(self, q: ArrayLike, link: str) -> F64:
        """``T_root_link`` of one link: ``(*batch, 4, 4)``."""
        arr = check_q(self._model, q)
        if arr.ndim == 1:
            i = self._model.link(link)
            fast = self._fast if self._fast_ready else self._fast_path()
            if fast is not None:
                return fast.fk_link(arr, i)
            sub, plan = self._path(i)
            T: F64 = fk_single(sub, plan, arr)[-1]
            return T
        Ts = self.fk(arr, links=[link])
        return Ts[..., 0, :, :]

    def jacobian(
        self,
        q: ArrayLike,
        link: str,
        *,
        point: ArrayLike = _ORIGIN,
        frame: JacobianFrame = "world",
    ) -> F64:
        """Geometric Jacobian ``(*batch, 6, n_q)`` of a point fixed on ``link``.

        Args:
            q: Shape ``(n_q,)`` or ``(*batch, n_q)``.
            link: The link.
            point: The point in the link frame [m] (default: the link origin).
            frame: ``"world"``: linear velocity of the point and angular velocity in root-frame
                axes; ``"local"``: both in the link's axes.
        """
        arr = check_q(self._model, q)
        i = self._model.link(link)
        if arr.ndim == 1 and point is _ORIGIN:
            return self._jacobian_single(arr, i, None, frame)
        p = np.asarray(point, dtype=np.float64).reshape(3)
        if arr.ndim == 1:
            return self._jacobian_single(arr, i, p, frame)
        flat = arr.reshape(math.prod(arr.shape[:-1]), self.n_q)
        J = jacobian_batch(self._model, flat, i, p, frame)
        J = J.reshape(*arr.shape[:-1], 6, self.n_q)
        J.setflags(write=False)
        return J

    def _jacobian_single(self, q: F64, link: int, p: F64 | None, frame: JacobianFrame) -> F64:
        chain = self._chain(link)  # also refuses floating and planar joints on the path
        fast = self._fast if self._fast_ready else self._fast_path()
        if fast is None:
            J = jacobian_single(chain, q, p, frame)
        else:
            R, _, J_mj = fast.pose_and_jacobian(q, link, p)
            J = J_mj.copy() if fast.identity_columns else J_mj @ fast.S
            J = to_frame(J, R, frame)
        J.setflags(write=False)
        return J

    def ik(
        self,
        T_root_target: ArrayLike,
        link: str,
        *,
        seed: ArrayLike | None = None,
        rng: int | np.random.Generator | None = None,
        options: IKOptions | None = None,
        **overrides: Unpack[IKOptionOverrides],
    ) -> IKResult:
        """Numerical IK: a configuration inside the limits that puts ``link`` at the target.

        Levenberg-Marquardt on the geometric Jacobian, every step clamped to the limits, from
        ``seed`` (default: the middle of the limits) and then from random configurations
        until ``restarts`` attempts or ``max_iterations`` iterations are used up (at most 60
        per attempt). The result depends only on the arguments (``rng`` seeds the restarts),
        not on the machine's speed, unless ``max_time_s`` is given. The result's ``q`` is
        always inside the limits; check ``success``.

        Args:
            T_root_target: 4x4 pose of the target in the root frame.
            link: The link to place.
            seed: Starting configuration ``(n_q,)``.
            rng: Seed or generator for the restarts (reproducible results).
            options: How to search (:class:`~robomodel.kinematics.IKOptions`, whose defaults
                are the defaults here).
            **overrides: Any field of :class:`~robomodel.kinematics.IKOptions`
                (``position_only``, ``tol_m``, ``tol_rad``, ``max_iterations``, ``max_time_s``,
                ``restarts``), overriding ``options``.

        Raises:
            KinematicsError: the target is not one finite 4x4 pose, or an option is invalid.
            UnknownNameError: ``link`` is not a link of the robot.
        """
        from robomodel.kinematics.ik import solve_ik

        resolved = (options or IKOptions()).replace(overrides)
        solver = self._ik_solver(link, resolved.position_only)
        return solve_ik(solver, self._model, T_root_target, seed=seed, rng=rng, options=resolved)

    def ik_batch(
        self,
        Ts_root_target: ArrayLike,
        link: str,
        *,
        seed: ArrayLike | None = None,
        rng: int | np.random.Generator | None = None,
        options: IKOptions | None = None,
        **overrides: Unpack[IKOptionOverrides],
    ) -> IKBatchResult:
        """IK for many targets ``(n, 4, 4)`` at once, vectorised over the targets.

        Same method and options as :meth:`ik`, with ``max_iterations`` per target; targets not
        solved after an attempt's iterations restart from random configurations until it is
        spent (``restarts`` does not bound a batch, and a batch has no ``max_time_s``).
        Returns an :class:`~robomodel.kinematics.ik.IKBatchResult` with one row per target.
        """
        from robomodel.kinematics.ik import solve_ik_batch

        resolved = (options or IKOptions()).replace(overrides)
        solver = self._ik_solver(link, resolved.position_only)
        return solve_ik_batch(
            solver, self._model, Ts_root_target, seed=seed, rng=rng, options=resolved
        )

    def ur_geometry(self, link: str) -> URGeometry:
        """The UR parameters measured on the chain to ``link``.

        Raises:
            NotAnalyticError: the chain is not a UR-type arm (the reason is in the message).
        """
        from robomodel.kinematics.ur import NotAnalyticError, ur_geometry

        found = self._analytic.get(link)
        if found is None:
            try:
                found = ur_geometry(self._model, self._model.link(link))
            except NotAnalyticError as exc:
                found = exc
            self._analytic[link] = found
        if isinstance(found, NotAnalyticError):
            raise NotAnalyticError(str(found))
        return found

    def analytic_ik(self, T_root_target: ArrayLike, link: str, *, tol: float = 1e-6) -> F64:
        """All analytic IK solutions ``(n_solutions, n_q)`` (UR-type arms: up to 8).

        Solutions outside the limits are dropped; for joints with a 2 pi range (UR's +-2 pi)
        the representative nearest 0 is returned. Every solution is checked by FK to
        ``tol`` [m and rad]. Other joints (off the chain) are 0, or their lower limit when 0
        is outside the limits. An empty result means the target is unreachable.

        Raises:
            NotAnalyticError: no analytic solver applies to the chain.
        """
        from robomodel.kinematics.ur import solve_ur

        geometry = self.ur_geometry(link)
        T = np.asarray(T_root_target, dtype=np.float64)
        if T.shape != (4, 4) or not np.isfinite(T).all():
            raise KinematicsError(f"the target must be a finite 4x4 pose, got shape {T.shape}")
        return solve_ur(self._model, self._model.link(link), geometry, T, tol=tol)

    def _ik_solver(self, link: str, position_only: bool) -> Solver:
        """The per-link IK constants, built on first use and kept."""
        key = (link, position_only)
        solver = self._solvers.get(key)
        if solver is None:
            from robomodel.kinematics.ik import Solver

            mujoco = None if self._backend == "numpy" else load_mujoco()
            solver = Solver(self._model, link, position_only, self.neutral(), mujoco)
            self._solvers[key] = solver
        return solver

    def __repr__(self) -> str:
        return (
            f"Kinematics(robot={self._robot.name!r}, n_q={self.n_q}, "
            f"n_links={len(self.link_names)}, root={self.root_link!r})"
        )
