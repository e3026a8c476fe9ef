"""A headless OpenGL context for MuJoCo's offscreen renderer: EGL, else OSMesa.

``MUJOCO_GL`` chooses as in MuJoCo (``egl``, ``osmesa``, ``glfw``); unset, EGL is tried, then
OSMesa. MuJoCo fixes its own choice when it is imported (``mujoco.gl_context``), before any
camera exists, and its default there is GLFW, which needs a display: robomodel makes the context
itself from ``mujoco.egl`` / ``mujoco.osmesa``. PyOpenGL binds one platform per process, so a
failed EGL attempt is forgotten (its ``OpenGL`` modules dropped) before OSMesa is tried, and the
choice is written to ``MUJOCO_GL`` for MuJoCo's C side (and for child processes).
"""

from __future__ import annotations

import atexit
import contextlib
import ctypes.util
import importlib
import os
import sys
import weakref
from typing import Any

from robomodel.sim.exceptions import SimulationError

__all__ = ["RenderingUnavailableError", "check_rendering", "gl_context"]

# backend -> (the library it loads, the Debian packages that provide a software renderer)
_BACKENDS = {"egl": ("EGL", "libegl1 libegl-mesa0"), "osmesa": ("OSMesa", "libosmesa6")}
_chosen: str | None = None
_live: weakref.WeakSet[Any] = weakref.WeakSet()


@atexit.register
def _free_all() -> None:
    """Free the contexts still open while PyOpenGL can (MuJoCo's OSMesa context, left to its
    ``__del__`` at interpreter shutdown, prints an ignored ctypes error)."""
    for context in list(_live):
        with contextlib.suppress(Exception):  # exiting anyway
            context.free()


class RenderingUnavailableError(SimulationError):
    """No offscreen OpenGL works in this process (the message names what to install)."""


def _forget_opengl(loaded_before: set[str], platform_was_set: bool) -> None:
    """Drop the modules a failed attempt imported (PyOpenGL bound to its platform)."""
    for name in set(sys.modules) - loaded_before:
        del sys.modules[name]
    if not platform_was_set:
        os.environ.pop("PYOPENGL_PLATFORM", None)


def _try(backend: str, width: int, height: int) -> Any:
    if backend in _BACKENDS and ctypes.util.find_library(_BACKENDS[backend][0]) is None:
        raise OSError(f"lib{_BACKENDS[backend][0]} not found")
    if backend in _BACKENDS:
        module = importlib.import_module(f"mujoco.{backend}")
        context = module.GLContext(width, height)
    else:  # glfw and the like: MuJoCo's own choice from MUJOCO_GL
        from robomodel.sim._mujoco import mujoco

        context = mujoco().GLContext(width, height)
    context.make_current()
    return context


def gl_context(width: int, height: int) -> Any:
    """A new offscreen GL context, current on this thread (see the module docstring).

    Raises:
        RenderingUnavailableError: No backend works; the message names the packages.
    """
    global _chosen
    asked = os.environ.get("MUJOCO_GL", "").strip().lower()
    candidates = [_chosen] if _chosen else ([asked] if asked else ["egl", "osmesa"])
    reasons: list[str] = []
    for backend in candidates:
        platform_was_set = "PYOPENGL_PLATFORM" in os.environ
        loaded_before = set(sys.modules)
        try:
            context = _try(backend, width, height)
        except Exception as exc:  # ImportError, OSError, PyOpenGL's errors: try the next
            first_line = str(exc).splitlines()[0].rstrip(".") if str(exc) else type(exc).__name__
            reasons.append(f"{backend}: {first_line}")
            if backend != candidates[-1]:
                _forget_opengl(loaded_before, platform_was_set)
            continue
        _chosen = backend
        _live.add(context)
        # MuJoCo's C side loads the GL functions by MUJOCO_GL too (else the first of
        # OSMesa/EGL/GLX found in the process: EGL after a failed EGL attempt)
        os.environ.setdefault("MUJOCO_GL", backend)
        return context
    packages = " or ".join(_BACKENDS[b][1] for b in candidates if b in _BACKENDS)
    raise RenderingUnavailableError(
        "simulated cameras need offscreen OpenGL and none works here "
        f"({'; '.join(reasons)}): install Debian's {packages or 'libegl1 libegl-mesa0'}"
        " (or set MUJOCO_GL to a backend that works)"
    )


def check_rendering() -> None:
    """Choose the backend now (once per process), so that a simulation with cameras fails
    when it is built, with the message of :func:`gl_context`, not in its stepping loop."""
    if _chosen is None:
        gl_context(1, 1).free()  # free() also releases it from this thread
