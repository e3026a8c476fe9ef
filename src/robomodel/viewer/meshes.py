"""Mesh files (STL, DAE, OBJ, ...) read through trimesh, resolved and cached.

A mesh becomes a tuple of :class:`MeshPart` (one per geometry of the file, with the file's
own scene transforms applied and the geometry's own colour, if it has one). The URDF scale is
not applied here but when drawing, so one cached file serves every scale. The cache is keyed
by the resolved path and the file's (mtime, size): a reload re-reads only meshes that changed.
"""

from __future__ import annotations

import os
import threading
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from robomodel._files import UserFileError, check_user_file
from robomodel.description.packages import PackageIndex
from robomodel.viewer._deps import import_trimesh
from robomodel.viewer.errors import MeshLoadError

__all__ = ["MeshCache", "MeshPart", "resolve_mesh_uri"]

Rgba = tuple[float, float, float, float]


@dataclass(frozen=True, slots=True)
class MeshPart:
    """One drawable piece of a mesh file.

    ``vertices`` has shape (V, 3) [m, before the URDF scale], ``faces`` shape (F, 3); both
    read-only. ``rgba`` is the geometry's own colour in [0, 1], or ``None``. ``glb`` is the
    part as binary glTF with its texture image and UVs when the file gives it a texture (a
    textured DAE or OBJ), so the viewer draws the texture as RViz does.
    """

    vertices: NDArray[np.float32]
    faces: NDArray[np.uint32]
    rgba: Rgba | None
    glb: bytes | None = None  # the part with its texture (binary glTF), if it has one


def resolve_mesh_uri(index: PackageIndex, uri: str, base_dir: Path) -> Path:
    """Resolve a mesh ``filename`` (``package://``, ``file://``, absolute or relative).

    ``package:///pkg/...`` (three slashes, found in some published URDFs) is read as
    ``package://pkg/...``, as yourdfpy and pinocchio do.

    Raises:
        PackageNotFoundError: unknown package.
        PathEscapeError: the path leaves its package directory.
    """
    if uri.startswith("package:///"):
        uri = "package://" + uri[len("package:///") :]
    return index.resolve(uri, base_dir=base_dir)


def _color_of(mesh: Any) -> Rgba | None:
    visual = getattr(mesh, "visual", None)
    if visual is None or not getattr(visual, "defined", False):
        return None
    color: Any = None
    if getattr(visual, "kind", None) == "texture":
        material = getattr(visual, "material", None)
        color = getattr(material, "main_color", None)
    else:
        color = getattr(visual, "main_color", None)
    if color is None:
        return None
    r, g, b, a = (float(c) / 255.0 for c in np.asarray(color, dtype=np.float64)[:4])
    return (r, g, b, a)


def _texture_of(mesh: Any) -> Any:
    """The texture image of a trimesh mesh (PBR base colour or simple image), or None."""
    visual = getattr(mesh, "visual", None)
    if getattr(visual, "kind", None) != "texture" or getattr(visual, "uv", None) is None:
        return None
    material = getattr(visual, "material", None)
    return getattr(material, "baseColorTexture", None) or getattr(material, "image", None)


def _part(mesh: Any) -> MeshPart:
    vertices = np.ascontiguousarray(mesh.vertices, dtype=np.float32)
    faces = np.ascontiguousarray(mesh.faces, dtype=np.uint32)
    vertices.setflags(write=False)
    faces.setflags(write=False)
    glb = None
    if _texture_of(mesh) is not None:
        try:
            glb = bytes(mesh.export(file_type="glb"))
        except Exception:  # an image trimesh cannot encode: drawn in its colour instead
            glb = None
    return MeshPart(vertices, faces, _color_of(mesh), glb)


def load_mesh_file(path: Path) -> tuple[MeshPart, ...]:
    """Read a mesh file into parts (scene transforms applied).

    Raises:
        MeshLoadError: the file cannot be parsed as a mesh or holds no triangles.
    """
    trimesh = import_trimesh()
    try:
        check_user_file(path, what="mesh file")
    except UserFileError as exc:
        raise MeshLoadError(str(path), exc.reason) from None
    try:
        loaded = trimesh.load(str(path))
    except Exception as exc:  # trimesh raises many unrelated types for bad files
        raise MeshLoadError(str(path), f"{type(exc).__name__}: {exc}") from None
    parts: list[MeshPart] = []
    if isinstance(loaded, trimesh.Scene):
        for node in loaded.graph.nodes_geometry:
            T, geometry_name = loaded.graph[node]
            geometry = loaded.geometry.get(geometry_name)
            if not isinstance(geometry, trimesh.Trimesh) or len(geometry.faces) == 0:
                continue
            mesh = geometry.copy()
            mesh.apply_transform(T)
            parts.append(_part(mesh))
    elif isinstance(loaded, trimesh.Trimesh) and len(loaded.faces) > 0:
        parts.append(_part(loaded))
    if not parts:
        raise MeshLoadError(str(path), "no triangles in the file")
    return tuple(parts)


class MeshCache:
    """Loaded mesh files keyed by resolved path and (mtime, size); safe across threads."""

    def __init__(self) -> None:
        self._parts: dict[tuple[str, int, int], tuple[MeshPart, ...]] = {}
        self._lock = threading.Lock()
        self.loads = 0

    def get(self, path: Path) -> tuple[MeshPart, ...]:
        """The parts of the mesh file at ``path``, reading it only when new or changed.

        Raises:
            FileNotFoundError: no such file.
            MeshLoadError: the file is not a readable mesh.
        """
        st = os.stat(path)
        key = (os.path.abspath(path), st.st_mtime_ns, st.st_size)
        with self._lock:
            cached = self._parts.get(key)
        if cached is not None:
            return cached
        parts = load_mesh_file(path)
        with self._lock:
            self._parts[key] = parts
            self.loads += 1
        return parts

    def snapshot(self) -> Mapping[tuple[str, int, int], tuple[MeshPart, ...]]:
        with self._lock:
            return dict(self._parts)
