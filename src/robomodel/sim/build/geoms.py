"""URDF geometry to MuJoCo geoms (collision and, optionally, visual).

MuJoCo sizes are half sizes (box half extents, cylinder ``[r, half length]``). Meshes are
loaded with trimesh (``.dae`` through pycollada, which MuJoCo's own importer cannot read) and
given to MuJoCo as vertices and faces, so ``package://`` paths and every trimesh format work.
"""

from __future__ import annotations

import importlib
import os
from dataclasses import dataclass
from typing import Any

import numpy as np

from robomodel._files import UserFileError, check_user_file
from robomodel.description.model import Box, Capsule, Cylinder, Geometry, Mesh, Sphere
from robomodel.description.packages import PackageIndex
from robomodel.errors import MissingDependencyError, RobomodelError
from robomodel.sim.exceptions import SimulationError

__all__ = ["MeshLoader", "geom_kwargs"]


@dataclass
class MeshLoader:
    """Loads mesh files once per (path, scale) and registers them in a spec.

    Args:
        index: Resolves ``package://`` URIs.
        base_dir: Directory of the description, for relative paths.
    """

    index: PackageIndex
    base_dir: str | None = None

    def __post_init__(self) -> None:
        self._names: dict[tuple[str, tuple[float, float, float]], str] = {}

    def mesh_name(self, spec: Any, mesh: Mesh, where: str) -> str:
        """The name of the spec mesh for ``mesh`` (added on first use)."""
        try:
            path = str(self.index.resolve(mesh.filename, base_dir=self.base_dir))
        except RobomodelError as exc:
            raise SimulationError(f"mesh '{mesh.filename}': {exc}", where=where) from None
        scale = mesh.scale or (1.0, 1.0, 1.0)
        key = (path, scale)
        if key in self._names:
            return self._names[key]
        if not os.path.isfile(path):
            raise SimulationError(
                f"mesh file '{mesh.filename}' not found (resolved to {path}); fix the path or "
                "use a primitive <box>/<cylinder>/<sphere> collision",
                where=where,
            )
        vertices, faces = _load(path, where)
        name = f"mesh{len(self._names)}_{os.path.basename(path)}"
        m = spec.add_mesh(name=name)
        m.uservert = (vertices * np.asarray(scale)).ravel().tolist()
        m.userface = faces.ravel().tolist()
        self._names[key] = name
        return name


def _load(path: str, where: str) -> tuple[np.ndarray, np.ndarray]:
    try:
        trimesh = importlib.import_module("trimesh")
    except ImportError:
        raise MissingDependencyError("trimesh", "sim", "loading mesh files") from None
    try:
        check_user_file(path, what="mesh file")
    except UserFileError as exc:
        raise SimulationError(str(exc), where=where) from None
    try:
        loaded = trimesh.load(path, force="mesh")
    except Exception as exc:
        raise SimulationError(f"cannot load mesh '{path}': {exc}", where=where) from None
    vertices = np.asarray(loaded.vertices, dtype=float)
    faces = np.asarray(loaded.faces, dtype=np.int64)
    if len(vertices) < 4 or len(faces) == 0:
        raise SimulationError(f"mesh '{path}' has no volume (too few vertices)", where=where)
    return vertices, faces


def geom_kwargs(spec: Any, geometry: Geometry, loader: MeshLoader, where: str) -> dict[str, Any]:
    """``type``/``size`` (or ``meshname``) arguments of ``body.add_geom`` for ``geometry``."""
    mj = importlib.import_module("mujoco")
    g = mj.mjtGeom
    if isinstance(geometry, Box):
        return {"type": g.mjGEOM_BOX, "size": [s / 2.0 for s in geometry.size_m]}
    if isinstance(geometry, Cylinder):
        return {"type": g.mjGEOM_CYLINDER, "size": [geometry.radius_m, geometry.length_m / 2, 0]}
    if isinstance(geometry, Sphere):
        return {"type": g.mjGEOM_SPHERE, "size": [geometry.radius_m, 0, 0]}
    if isinstance(geometry, Capsule):
        return {"type": g.mjGEOM_CAPSULE, "size": [geometry.radius_m, geometry.length_m / 2, 0]}
    if isinstance(geometry, Mesh):
        return {"type": g.mjGEOM_MESH, "meshname": loader.mesh_name(spec, geometry, where)}
    raise SimulationError(f"unsupported geometry {type(geometry).__name__}", where=where)
