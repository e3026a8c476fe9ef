"""``import mujoco`` without its OpenGL probe.

With ``MUJOCO_GL`` unset, importing MuJoCo loads GLFW for its default ``GLContext``, and the
``glfw`` package checks its bundled library's version by starting a Python subprocess: about
a tenth of a second, and an X11 library loaded, in every process that computes kinematics or
starts a simulation. robomodel makes its offscreen contexts itself (``sim.sensors._gl``, EGL
then OSMesa), so the import runs with ``MUJOCO_GL=disable`` when the user has not chosen a
backend, and the variable is unset again afterwards.
"""

from __future__ import annotations

import importlib
import os
from typing import Any

__all__ = ["import_mujoco"]


def import_mujoco() -> Any:
    """The ``mujoco`` module. Raises ImportError when it is not installed."""
    if "MUJOCO_GL" in os.environ:
        return importlib.import_module("mujoco")
    os.environ["MUJOCO_GL"] = "disable"
    try:
        return importlib.import_module("mujoco")
    finally:
        if os.environ.get("MUJOCO_GL") == "disable":
            del os.environ["MUJOCO_GL"]
