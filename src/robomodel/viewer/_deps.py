"""Lazy imports of the viewer's optional back-ends, with an error naming the extra."""

from __future__ import annotations

import importlib
from typing import Any

from robomodel.errors import MissingDependencyError

__all__ = ["import_trimesh", "import_viser"]


def _import(module: str, purpose: str) -> Any:
    try:
        return importlib.import_module(module)
    except ModuleNotFoundError as exc:
        if exc.name is not None and exc.name.split(".")[0] == module:
            raise MissingDependencyError(module, "viewer", purpose) from None
        raise


def import_viser() -> Any:
    """The ``viser`` module (the web 3D viewer)."""
    return _import("viser", "robomodel view")


def import_trimesh() -> Any:
    """The ``trimesh`` module (STL, DAE and OBJ mesh loading)."""
    return _import("trimesh", "loading meshes in robomodel view")
