"""What a ``visualization_msgs/Marker`` looks like, as viser scene nodes in the marker's frame.

Shapes and sizes follow RViz's marker classes (rviz_default_plugins ``markers/*.cpp``):

- ARROW (0): along +x, ``scale.x`` long, shaft ``scale.y`` by ``scale.z`` thick, head twice
  as thick, 0.77 : 0.23 shaft to head (ArrowMarker::setDefaultProportions); with two
  ``points``, from the first to the second, shaft diameter ``scale.x``, head diameter
  ``scale.y``, head length ``scale.z`` (0: 0.23 of the length).
- CUBE (1), SPHERE (2), CYLINDER (3, along z): centred, ``scale`` the full extents.
- LINE_STRIP (4), LINE_LIST (5): ``scale.x`` wide [m]; ``colors`` per point when given.
- CUBE_LIST (6), SPHERE_LIST (7): one shape of ``scale`` at each point.
- POINTS (8): squares ``scale.x`` wide.
- TEXT_VIEW_FACING (9): ``text`` in ``color``, lines ``scale.z`` high, centred, facing the
  camera (text_view_facing_marker.cpp): an image of the text (:mod:`.text_image`), turned to
  the page's camera by the display (``Drawable.view_facing``).
- MESH_RESOURCE (10): ``mesh_resource`` scaled by ``scale``, in ``color`` unless
  ``mesh_use_embedded_materials``: then the mesh's own materials (its colour, or its texture:
  the part's binary glTF) tinted by a non-zero ``color`` as RViz 2 tints them, and parts
  without one in RViz's default material (:mod:`.mesh_tint`; mesh_resource_marker.cpp
  useClonedMaterials, updateMaterialColor).
- TRIANGLE_LIST (11): every three ``points`` a triangle.

Each builder returns :class:`Drawable` s: a scene method (``mesh_simple``, ``line_segments``,
...) and its arguments, placed by the caller at the marker's pose in the fixed frame.
"""

from __future__ import annotations

import dataclasses
import functools
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from robomodel.viewer._deps import import_trimesh
from robomodel.viewer.displays.mesh_tint import (
    embedded_tint,
    tinted_glb,
    tinted_rgb,
    without_material,
)
from robomodel.viewer.displays.text_image import text_image
from robomodel.viewer.limits import MAX_MARKER_POINTS, truncated_text

__all__ = ["MARKER_TYPES", "Drawable", "MarkerShapeError", "bounded_marker", "marker_drawables"]

MARKER_TYPES = {
    0: "ARROW", 1: "CUBE", 2: "SPHERE", 3: "CYLINDER", 4: "LINE_STRIP", 5: "LINE_LIST",
    6: "CUBE_LIST", 7: "SPHERE_LIST", 8: "POINTS", 9: "TEXT_VIEW_FACING", 10: "MESH_RESOURCE",
    11: "TRIANGLE_LIST",
}  # fmt: skip


class MarkerShapeError(ValueError):
    """A marker that cannot be drawn (RViz's status text for it)."""


@dataclass(frozen=True, slots=True)
class Drawable:
    """``scene.add_<kind>(name, **kwargs)`` in the marker's frame (``view_facing``: turned
    to the camera instead of the marker's orientation)."""

    kind: str
    kwargs: dict[str, Any]
    view_facing: bool = False


Mesh = tuple[NDArray[np.float32], NDArray[np.uint32]]


@dataclass(frozen=True, slots=True)
class _Rgba:
    """A colour as ``std_msgs/ColorRGBA`` holds it (0..1 each)."""

    r: float
    g: float
    b: float
    a: float


def _rgb_alpha(color: Any) -> tuple[tuple[int, int, int], float]:
    rgb = tuple(round(min(1.0, max(0.0, float(v))) * 255) for v in (color.r, color.g, color.b))
    return (rgb[0], rgb[1], rgb[2]), min(1.0, max(0.0, float(color.a)))


def _points(msg: Any) -> NDArray[np.float64]:
    return np.array([(p.x, p.y, p.z) for p in msg.points], dtype=np.float64).reshape(-1, 3)


def _point_colors(msg: Any) -> NDArray[np.uint8]:
    """One RGB per point: ``colors`` when it has one per point, else ``color``."""
    n = len(msg.points)
    if len(msg.colors) == n and n:
        rgba = np.array([(c.r, c.g, c.b) for c in msg.colors], dtype=np.float64)
        rgba_u8: NDArray[np.uint8] = (np.clip(rgba, 0.0, 1.0) * 255).round().astype(np.uint8)
        return rgba_u8
    rgb, _ = _rgb_alpha(msg.color)
    return np.tile(np.array(rgb, dtype=np.uint8), (n, 1))


@functools.cache
def _unit(shape: str) -> Mesh:
    """Unit shapes (1 m extents, centred) from trimesh; arrows' parts along +z."""
    creation = import_trimesh().creation
    if shape == "box":
        mesh = creation.box(extents=(1.0, 1.0, 1.0))
    elif shape == "sphere":
        mesh = creation.icosphere(subdivisions=2, radius=0.5)
    elif shape == "cylinder":
        mesh = creation.cylinder(radius=0.5, height=1.0, sections=24)
    else:  # cone: base at z=0, tip at z=1
        mesh = creation.cone(radius=0.5, height=1.0, sections=24)
    vertices = np.asarray(mesh.vertices, dtype=np.float32)
    faces = np.asarray(mesh.faces, dtype=np.uint32)
    vertices.setflags(write=False)
    faces.setflags(write=False)
    return vertices, faces


def _scaled(shape: str, scale: Any, offset: Any = (0.0, 0.0, 0.0)) -> Mesh:
    vertices, faces = _unit(shape)
    return (vertices * np.asarray(scale, np.float32) + np.asarray(offset, np.float32), faces)


def _merge(meshes: list[Mesh]) -> Mesh:
    vertices, faces, base = [], [], 0
    for v, f in meshes:
        vertices.append(v)
        faces.append(f + base)
        base += len(v)
    return np.concatenate(vertices).astype(np.float32), np.concatenate(faces).astype(np.uint32)


def _arrow_along_z(shaft_len: float, shaft_d: tuple[float, float], head_len: float, head_d: tuple[float, float]) -> Mesh:  # fmt: skip
    shaft = _scaled("cylinder", (shaft_d[0], shaft_d[1], shaft_len), (0, 0, shaft_len / 2))
    head = _scaled("cone", (head_d[0], head_d[1], head_len), (0, 0, shaft_len))
    return _merge([shaft, head])


def _solid(mesh: Mesh, color: Any, *, side: str = "front") -> Drawable:
    rgb, alpha = _rgb_alpha(color)
    kwargs: dict[str, Any] = {"vertices": mesh[0], "faces": mesh[1], "color": rgb, "side": side}
    if alpha < 1.0:
        kwargs["opacity"] = alpha
    return Drawable("mesh_simple", kwargs)


def _arrow(msg: Any, _load: Any) -> list[Drawable]:
    s = msg.scale
    if len(msg.points) == 1:
        raise MarkerShapeError("Arrow marker takes 0 or 2 points, not 1")
    if len(msg.points) >= 2:
        p0, p1 = _points(msg)[:2]
        length = float(np.linalg.norm(p1 - p0))
        head = 0.23 * length if s.z == 0.0 else max(0.0, min(float(s.z), length))
        mesh = _arrow_along_z(length - head, (s.x, s.x), head, (s.y, s.y))
        direction = (p1 - p0) / length if length > 0 else np.array([0.0, 0.0, 1.0])
        vertices = mesh[0] @ _rotation_z_to(direction).T.astype(np.float32) + p0.astype(np.float32)  # fmt: skip
        return [_solid((vertices.astype(np.float32), mesh[1]), msg.color)]
    mesh = _arrow_along_z(0.77 * s.x, (s.y, s.z), 0.23 * s.x, (2 * s.y, 2 * s.z))
    # +z to +x: (x, y, z) -> (z, x, y) is a rotation (a cyclic permutation).
    return [_solid((mesh[0][:, [2, 0, 1]].copy(), mesh[1]), msg.color)]


def _rotation_z_to(direction: NDArray[np.float64]) -> NDArray[np.float64]:
    """A rotation taking +z to the unit vector ``direction``."""
    z = np.array([0.0, 0.0, 1.0])
    v, c = np.cross(z, direction), float(np.dot(z, direction))
    if c < -1.0 + 1e-9:
        return np.diag([1.0, -1.0, -1.0])
    vx = np.array([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]])
    R: NDArray[np.float64] = np.eye(3) + vx + vx @ vx / (1.0 + c)
    return R


def _shape(shape: str) -> Callable[[Any, Any], list[Drawable]]:
    def build(msg: Any, _load: Any) -> list[Drawable]:
        s = msg.scale
        return [_solid(_scaled(shape, (s.x, s.y, s.z)), msg.color)]

    return build


def _lines(pairs: bool) -> Callable[[Any, Any], list[Drawable]]:
    def build(msg: Any, _load: Any) -> list[Drawable]:
        points, colors = _points(msg), _point_colors(msg)
        if pairs:
            n = len(points) // 2 * 2
            segments, seg_colors = points[:n].reshape(-1, 2, 3), colors[:n].reshape(-1, 2, 3)
        else:
            segments = np.stack([points[:-1], points[1:]], axis=1)
            seg_colors = np.stack([colors[:-1], colors[1:]], axis=1)
        if len(segments) == 0:
            return []
        return [Drawable("line_segments", {"points": segments.astype(np.float32), "colors": seg_colors, "thickness": max(float(msg.scale.x), 1e-4), "thickness_units": "world"})]  # fmt: skip

    return build


def _list_of(shape: str) -> Callable[[Any, Any], list[Drawable]]:
    def build(msg: Any, _load: Any) -> list[Drawable]:
        points, colors = _points(msg), _point_colors(msg)
        if len(points) == 0:
            return []
        s = (msg.scale.x, msg.scale.y, msg.scale.z)
        meshes = [_scaled(shape, s, p) for p in points]
        per_vertex = np.repeat(colors, [len(m[0]) for m in meshes], axis=0)
        return [_colored(_merge(meshes), per_vertex, msg.color)]

    return build


def _colored(mesh: Mesh, vertex_rgb: NDArray[np.uint8], color: Any) -> Drawable:
    """A mesh with a colour per vertex (one colour: a simple mesh)."""
    if (vertex_rgb == vertex_rgb[0]).all():
        rgb = vertex_rgb[0]
        return _solid(mesh, _Rgba(rgb[0] / 255, rgb[1] / 255, rgb[2] / 255, color.a), side="double")
    trimesh = import_trimesh()
    alpha = np.full((len(vertex_rgb), 1), round(_rgb_alpha(color)[1] * 255), np.uint8)
    colored = trimesh.Trimesh(mesh[0], mesh[1], vertex_colors=np.hstack([vertex_rgb, alpha]), process=False)  # fmt: skip
    return Drawable("mesh_trimesh", {"mesh": colored})


def _points_marker(msg: Any, _load: Any) -> list[Drawable]:
    points = _points(msg)
    if len(points) == 0:
        return []
    return [Drawable("point_cloud", {"points": points.astype(np.float32), "colors": _point_colors(msg), "point_size": max(float(msg.scale.x), 1e-4), "point_shape": "square", "point_shading": "flat"})]  # fmt: skip


def _text(msg: Any, _load: Any) -> list[Drawable]:
    rgb, alpha = _rgb_alpha(msg.color)
    image = text_image(str(msg.text), rgb, alpha, max(float(msg.scale.z), 1e-3))
    kwargs = {"image": image.rgba, "render_width": image.width_m, "render_height": image.height_m, "format": "png", "cast_shadow": False, "receive_shadow": False}  # fmt: skip
    return [Drawable("image", kwargs, view_facing=True)]


def _triangles(msg: Any, _load: Any) -> list[Drawable]:
    points, colors = _points(msg), _point_colors(msg)
    if len(points) % 3:
        raise MarkerShapeError(f"Triangle list has {len(points)} points, not a multiple of 3")
    if len(points) == 0:
        return []
    s = np.array([msg.scale.x, msg.scale.y, msg.scale.z], np.float32)
    faces = np.arange(len(points), dtype=np.uint32).reshape(-1, 3)
    return [_colored(((points * s).astype(np.float32), faces), colors, msg.color)]


def _mesh_resource(msg: Any, load: Any) -> list[Drawable]:
    if not msg.mesh_resource:
        raise MarkerShapeError("Empty mesh_resource")
    if load is None:
        raise MarkerShapeError("Mesh resources are not loaded in this viewer")
    scale = np.array([msg.scale.x, msg.scale.y, msg.scale.z], np.float32)
    embedded = bool(msg.mesh_use_embedded_materials)
    c = msg.color
    tint = embedded_tint(float(c.r), float(c.g), float(c.b), float(c.a))
    out = []
    for part in load(str(msg.mesh_resource)):
        if embedded and part.glb is not None:  # its texture, tinted
            kwargs = {"glb_data": tinted_glb(part.glb, tint), "scale": tuple(float(v) for v in scale), "cast_shadow": False, "receive_shadow": False}  # fmt: skip
            out.append(Drawable("glb", kwargs))
            continue
        color = msg.color
        if embedded and part.rgba is not None:
            r, g, b = (float(v) for v in tinted_rgb(part.rgba[:3], tint))
            color = _Rgba(r, g, b, tint.opacity)
        elif embedded:  # RViz's default material stands in for a missing one
            rgb, opacity = without_material(float(c.r), float(c.g), float(c.b), float(c.a))
            color = _Rgba(*rgb, opacity)
        out.append(_solid((np.asarray(part.vertices) * scale, np.asarray(part.faces)), color))
    return out


_BUILDERS: dict[int, Callable[[Any, Any], list[Drawable]]] = {
    0: _arrow, 1: _shape("box"), 2: _shape("sphere"), 3: _shape("cylinder"), 4: _lines(False),
    5: _lines(True), 6: _list_of("box"), 7: _list_of("sphere"), 8: _points_marker, 9: _text,
    10: _mesh_resource, 11: _triangles,
}  # fmt: skip


def bounded_marker(msg: Any) -> tuple[Any, str]:
    """``msg`` within the viewer's bounds (:mod:`robomodel.viewer.limits`): its first
    ``MAX_MARKER_POINTS`` points and colors, its text truncated; and a note saying what was cut
    ("" and ``msg`` itself when nothing was)."""
    notes = []
    changes: dict[str, Any] = {}
    if len(msg.points) > MAX_MARKER_POINTS:
        changes["points"] = msg.points[:MAX_MARKER_POINTS]
        changes["colors"] = msg.colors[:MAX_MARKER_POINTS]
        notes.append(f"{len(msg.points)} points drawn truncated to the first {MAX_MARKER_POINTS}")
    if int(msg.type) == 9:
        text, note = truncated_text(str(msg.text))
        if note:
            changes["text"] = text
            notes.append(note)
    if not changes:
        return msg, ""
    return dataclasses.replace(msg, **changes), "; ".join(notes)


def marker_drawables(msg: Any, load_mesh: Callable[[str], tuple[Any, ...]] | None = None) -> list[Drawable]:  # fmt: skip
    """The scene nodes of ``msg`` in its own pose's frame.

    Raises:
        MarkerShapeError: an unknown type or a marker RViz refuses (RViz's status text).
        RobomodelError: its mesh resource cannot be read.
    """
    builder = _BUILDERS.get(int(msg.type))
    if builder is None:
        raise MarkerShapeError(f"Unknown marker type: {msg.type}")
    return builder(msg, load_mesh)
