"""A robot's configuration space: the layout of ``q``, its labels and its limits."""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np
from numpy.typing import ArrayLike, NDArray

from robomodel.description.model import UnknownNameError
from robomodel.kinematics._checks import check_q, q_labels
from robomodel.kinematics._compile import FLOATING, CompiledModel

__all__ = ["ConfigurationSpace"]

F64 = NDArray[np.float64]


class ConfigurationSpace:
    """Names, sizes and limits of the entries of ``q``, and configurations built from them.

    The base of :class:`~robomodel.kinematics.Kinematics`, which documents the layout of ``q``
    and sets ``_model``, the compiled model these read.
    """

    _model: CompiledModel

    @property
    def joint_names(self) -> tuple[str, ...]:
        """Actuated joints, in ``q`` order."""
        return self._model.joint_names

    @property
    def link_names(self) -> tuple[str, ...]:
        """Links in output order (depth-first from the root)."""
        return self._model.link_names

    @property
    def root_link(self) -> str:
        return self._model.link_names[0]

    @property
    def n_q(self) -> int:
        """Length of ``q`` (a floating joint counts 7, a planar joint 3)."""
        return self._model.n_q

    @property
    def q_names(self) -> tuple[str, ...]:
        """A label per entry of ``q`` (``joint`` or ``joint[k]``)."""
        return tuple(q_labels(self._model))

    @property
    def lower(self) -> F64:
        """``(n_q,)`` lower position limits [rad or m] (-inf where unlimited)."""
        return self._model.lower

    @property
    def upper(self) -> F64:
        """``(n_q,)`` upper position limits [rad or m] (+inf where unlimited)."""
        return self._model.upper

    @property
    def mimic(self) -> Mapping[str, tuple[str, float, float]]:
        """Mimic joints: name -> (actuated source, multiplier, offset), chains resolved."""
        return self._model.mimic

    def q_slice(self, joint: str) -> slice:
        """Where ``joint``'s values sit in ``q`` (``UnknownNameError`` for unknown names)."""
        try:
            k = self._model.joint_index[joint]
        except KeyError:
            raise UnknownNameError("actuated joint", joint, self.joint_names) from None
        start = self._model.q_start[k]
        return slice(start, start + self._model.q_size[k])

    def neutral(self) -> F64:
        """The zero configuration (identity quaternion for floating joints)."""
        q = np.zeros(self.n_q)
        for k, start in enumerate(self._model.q_start):
            if self._model.kind[self._link_of_joint(k)] == FLOATING:
                q[start + 6] = 1.0
        return q

    def _link_of_joint(self, k: int) -> int:
        return self._model.link_joint.index(self._model.joint_names[k])

    def q_from_dict(self, values: Mapping[str, float], *, base: ArrayLike | None = None) -> F64:
        """``q`` from ``{joint: value}`` (others from ``base``, default :meth:`neutral`).

        Mimic joints may not be given (they follow their source).
        """
        q = self.neutral() if base is None else np.array(check_q(self._model, base), copy=True)
        for name, value in values.items():
            if name in self._model.mimic:
                source = self._model.mimic[name][0]
                raise UnknownNameError(
                    f"actuated joint (mimic joints follow their source '{source}')",
                    name,
                    self.joint_names,
                )
            q[self.q_slice(name)] = value
        return q

    def random_q(
        self, n: int | None = None, *, seed: int | np.random.Generator | None = None
    ) -> F64:
        """Uniform random configurations within the limits (unlimited joints in [-pi, pi])."""
        rng = np.random.default_rng(seed)
        lo = np.where(np.isfinite(self.lower), self.lower, -math.pi)
        hi = np.where(np.isfinite(self.upper), self.upper, math.pi)
        shape = (self.n_q,) if n is None else (n, self.n_q)
        q: F64 = rng.uniform(lo, hi, size=shape)
        return q

    def within_limits(self, q: ArrayLike, *, tol: float = 0.0) -> NDArray[np.bool_]:
        """True where every value of a configuration is inside its limits (± ``tol``)."""
        arr = check_q(self._model, q)
        ok: NDArray[np.bool_] = np.all(
            (arr >= self.lower - tol) & (arr <= self.upper + tol), axis=-1
        )
        return ok

    def link_index(self, link: str) -> int:
        return self._model.link(link)
