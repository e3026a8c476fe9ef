"""Validating joint configurations and link names given to the kinematics API."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from numpy.typing import ArrayLike, NDArray

from robomodel.kinematics._compile import CompiledModel
from robomodel.kinematics.exceptions import ConfigurationError

__all__ = ["check_limits", "check_q", "q_labels"]


def q_labels(model: CompiledModel) -> list[str]:
    """A name per entry of ``q`` (``joint`` or ``joint[i]`` for multi-valued joints)."""
    labels: list[str] = []
    for name, size in zip(model.joint_names, model.q_size, strict=True):
        labels.extend([name] if size == 1 else [f"{name}[{k}]" for k in range(size)])
    return labels


def _surely_finite(q: NDArray[np.float64]) -> bool:
    """True when every value is finite; False also when a sum of huge values overflows.

    A sum of Python floats costs a fifth of ``np.isfinite(q).all()`` for a short ``q``.
    """
    if len(q) <= 64:
        return math.isfinite(sum(q.tolist()))
    return bool(np.isfinite(q).all())


def check_q(model: CompiledModel, q: ArrayLike) -> NDArray[np.float64]:
    """``q`` as float64 with shape ``(n_q,)`` or ``(*batch, n_q)``, all values finite."""
    if (
        type(q) is np.ndarray
        and q.dtype == np.float64
        and q.shape == (model.n_q,)
        and _surely_finite(q)
    ):
        return q  # the common single-configuration case, checked cheaply
    try:
        arr = np.asarray(q, dtype=np.float64)
    except (TypeError, ValueError) as exc:
        raise ConfigurationError(f"q must be an array of numbers: {exc}") from None
    if arr.ndim == 0 or arr.shape[-1] != model.n_q:
        raise ConfigurationError(
            f"q has shape {arr.shape}; expected ({model.n_q},) or (..., {model.n_q}) "
            f"for joints {', '.join(model.joint_names) or '(none)'}"
        )
    if not np.isfinite(arr).all():
        bad = np.argwhere(~np.isfinite(arr))[0]
        label = q_labels(model)[int(bad[-1])]
        where = f" at batch index {tuple(int(b) for b in bad[:-1])}" if arr.ndim > 1 else ""
        raise ConfigurationError(
            f"q has a non-finite value ({arr[tuple(bad)]}) for joint '{label}'{where}"
        )
    return arr


def check_limits(model: CompiledModel, q: NDArray[np.float64], tol: float = 0.0) -> None:
    """Raise :class:`ConfigurationError` naming the first value outside its joint's limits."""
    low = q < model.lower - tol
    high = q > model.upper + tol
    bad = np.argwhere(low | high)
    if len(bad):
        k = int(bad[0][-1])
        value = float(q[tuple(bad[0])])
        raise ConfigurationError(
            f"joint '{q_labels(model)[k]}' = {value!r} is outside its limits "
            f"[{float(model.lower[k])!r}, {float(model.upper[k])!r}]"
        )


def link_indices(model: CompiledModel, links: Sequence[str]) -> list[int]:
    """Indices of link names (``UnknownNameError`` lists the valid names)."""
    if isinstance(links, str):
        links = [links]
    return [model.link(name) for name in links]
