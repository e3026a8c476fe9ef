"""Lazy import of MuJoCo (the ``sim`` extra)."""

from __future__ import annotations

import logging
from typing import Any

from robomodel._mujoco_import import import_mujoco
from robomodel.errors import MissingDependencyError

__all__ = ["mujoco"]

_log = logging.getLogger("robomodel.sim")
_module: Any = None


def _warn(message: str) -> None:
    _log.warning("MuJoCo: %s", message)


def mujoco() -> Any:
    """The ``mujoco`` module, or :class:`MissingDependencyError` naming the ``sim`` extra.

    On first use, MuJoCo's warnings go to the ``robomodel.sim`` logger instead of a
    ``MUJOCO_LOG.TXT`` file in the working directory (unless a handler is already set);
    divergence itself is raised by the engine as :class:`~robomodel.sim.DivergenceError`.
    """
    global _module
    if _module is not None:  # called in the stepping loop: no import machinery after the first
        return _module
    try:
        module = import_mujoco()
    except ImportError:
        raise MissingDependencyError("mujoco", "sim", "the simulator") from None
    if module.get_mju_user_warning() is None:
        module.set_mju_user_warning(_warn)
    _module = module
    return module
