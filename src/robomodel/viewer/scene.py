"""The RobotModel display: a robot's visual and collision geometry as viser scene nodes.

Each link is one flat scene node, posed in the fixed frame every update (only links whose
pose changed are sent). Visuals and collisions hang below it at their ``<origin>``; the Visual
and Collision toggles hide those sub-trees and Alpha sets the opacity of every leaf, as RViz's
RobotModel display does. Meshes that cannot be found or read are skipped and reported in
:attr:`RobotModelDisplay.problems`; the rest of the robot is drawn.

A visual mesh whose *package* is not installed is drawn as its link's primitive collision
geometry (boxes, cylinders, spheres) instead, and recorded in
:attr:`RobotModelDisplay.substituted` (one status line per missing package). RViz draws
nothing there; a robot whose meshes come from an optional package (the UR5 example's
``ur_description``, from example-robot-data) still looks like itself.
"""

from __future__ import annotations

import threading
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Literal

import numpy as np
from numpy.typing import NDArray

from robomodel.description.model import Box, Capsule, Cylinder, Geometry, Mesh, Robot, Sphere
from robomodel.description.model.pose import Origin
from robomodel.description.packages import PackageIndex
from robomodel.errors import PackageNotFoundError, RobomodelError
from robomodel.viewer._poses import wxyz_xyz_from_matrix
from robomodel.viewer.materials import DEFAULT_RGBA, material_rgba, rgb255
from robomodel.viewer.meshes import MeshCache, resolve_mesh_uri
from robomodel.viewer.pose_messages import write_pose

__all__ = ["GeometryProblem", "RobotModelDisplay"]

Kind = Literal["visual", "collision"]
Rgba = tuple[float, float, float, float]
_POSITION_TOL_M = 1e-6
# RViz draws no shadows, and software WebGL renders much faster without them.
_NO_SHADOWS: dict[str, Any] = {"cast_shadow": False, "receive_shadow": False}


_ROTATION_TOL = 1e-7


@dataclass(frozen=True, slots=True)
class GeometryProblem:
    """A geometry that could not be drawn (a missing or unreadable mesh, a refused path)."""

    link: str
    kind: Kind
    uri: str
    reason: str

    def format(self) -> str:
        return f"{self.link} ({self.kind}): {self.uri}: {self.reason}"


@dataclass(slots=True)
class _Leaf:
    handle: Any
    rgba: Rgba


@dataclass(frozen=True, slots=True)
class _PendingMesh:
    node: str
    link: str
    kind: Kind
    geometry: Mesh
    rgba: Rgba | None
    visible: bool


class RobotModelDisplay:
    """Draws one robot below the scene node ``root``.

    Args:
        scene: viser's scene API (``server.scene``).
        root: Scene-tree name for this robot, e.g. ``/robots/0``.
        robot: The description.
        index: Resolves ``package://`` mesh paths.
        base_dir: Directory that relative mesh paths are relative to.
        meshes: Shared mesh cache.
    """

    def __init__(
        self,
        scene: Any,
        root: str,
        robot: Robot,
        *,
        index: PackageIndex,
        base_dir: Path,
        meshes: MeshCache,
        alpha: float = 1.0,
        show_visual: bool = True,
        show_collision: bool = False,
    ) -> None:
        self.scene = scene
        self.root = root
        self.robot = robot
        self.index = index
        self.base_dir = base_dir
        self.meshes = meshes
        self.alpha = alpha
        self.show_visual = show_visual
        self.show_collision = show_collision
        self.shown = True  # a RobotModel display shows it (its root node's visibility)
        self._root: Any = None
        self.problems: list[GeometryProblem] = []
        # (missing package, link) of visual meshes drawn as the link's collision primitives
        self.substituted: list[tuple[str, str]] = []
        self.mesh_nodes: list[str] = []  # scene names of the mesh parts drawn so far
        self.link_names = robot.link_names
        self._links: list[Any] = []
        self._groups: dict[Kind, list[Any]] = {"visual": [], "collision": []}
        self._leaves: list[_Leaf] = []
        self._pending: list[_PendingMesh] = []
        self._loading = 0  # meshes taken from _pending, not drawn yet
        self._deferred: list[_PendingMesh] = []
        self._lock = threading.Lock()
        self._last_wxyz = np.full((len(self.link_names), 4), np.nan)
        self._last_xyz = np.full((len(self.link_names), 3), np.nan)
        self._last_visible = np.zeros(len(self.link_names), dtype=bool)
        self._removed = False

    # -- building -----------------------------------------------------------------------------
    def build(self) -> None:
        """Add link nodes and primitives now; meshes wait for :meth:`load_meshes`."""
        self._root = self.scene.add_frame(self.root, show_axes=False, visible=self.shown)
        for i, link in enumerate(self.robot.links):
            node = f"{self.root}/l{i}"
            self._links.append(self.scene.add_frame(node, show_axes=False, visible=False))
            link_rgba: Rgba | None = None
            for k, visual in enumerate(link.visuals):
                rgba = material_rgba(visual.material, self.robot)
                link_rgba = link_rgba or rgba
                self._add_geometry(
                    f"{node}/v{k}", link.name, "visual", visual.geometry, visual.origin, rgba
                )
            for k, collision in enumerate(link.collisions):
                self._add_geometry(
                    f"{node}/c{k}",
                    link.name,
                    "collision",
                    collision.geometry,
                    collision.origin,
                    link_rgba,
                )

    def _add_geometry(
        self,
        node: str,
        link: str,
        kind: Kind,
        geometry: Geometry,
        origin: Origin,
        rgba: Rgba | None,
    ) -> None:
        wxyz, xyz = wxyz_xyz_from_matrix(origin.matrix())
        visible = self.show_visual if kind == "visual" else self.show_collision
        group = self.scene.add_frame(
            node, show_axes=False, wxyz=wxyz, position=xyz, visible=visible
        )
        self._groups[kind].append(group)
        if isinstance(geometry, Mesh):
            self._pending.append(_PendingMesh(node, link, kind, geometry, rgba, visible))
            return
        color = rgba or DEFAULT_RGBA
        common = {"color": rgb255(color), "opacity": self._opacity(color), **_NO_SHADOWS}
        if isinstance(geometry, Box):
            handle = self.scene.add_box(f"{node}/g", dimensions=geometry.size_m, **common)
            self._leaves.append(_Leaf(handle, color))
        elif isinstance(geometry, Sphere):
            handle = self.scene.add_icosphere(
                f"{node}/g", radius=geometry.radius_m, subdivisions=3, **common
            )
            self._leaves.append(_Leaf(handle, color))
        elif isinstance(geometry, Cylinder):
            handle = self.scene.add_cylinder(
                f"{node}/g",
                radius=geometry.radius_m,
                height=geometry.length_m,
                radial_segments=32,
                **common,
            )
            self._leaves.append(_Leaf(handle, color))
        elif isinstance(geometry, Capsule):
            self._add_capsule(node, geometry, color, common)

    def _add_capsule(
        self, node: str, geometry: Capsule, color: Rgba, common: dict[str, Any]
    ) -> None:
        body = self.scene.add_cylinder(
            f"{node}/g", radius=geometry.radius_m, height=geometry.length_m, **common
        )
        self._leaves.append(_Leaf(body, color))
        for j, z in enumerate((geometry.length_m / 2, -geometry.length_m / 2)):
            cap = self.scene.add_icosphere(
                f"{node}/cap{j}",
                radius=geometry.radius_m,
                subdivisions=3,
                position=(0.0, 0.0, z),
                **common,
            )
            self._leaves.append(_Leaf(cap, color))

    def load_meshes(self) -> None:
        """Resolve, read (through the cache) and add every mesh; record what fails.

        Collision meshes wait until Collision Enabled is first switched on: most of the time
        nobody looks at them, and they would double what a big robot sends to the browser.
        """
        while True:
            with self._lock:
                if self._removed or not self._pending:
                    return
                item = self._pending.pop(0)
                if item.kind == "collision" and not self.show_collision:
                    self._deferred.append(item)
                    continue
                self._loading += 1  # still pending until drawn (pending_meshes)
            try:
                self._add_mesh(item)
            finally:
                with self._lock:
                    self._loading -= 1

    def _add_mesh(self, item: _PendingMesh) -> None:
        uri = item.geometry.filename
        try:
            path = resolve_mesh_uri(self.index, uri, self.base_dir)
            parts = self.meshes.get(path)
        except PackageNotFoundError as exc:
            if not (item.kind == "visual" and self._substitute(item, exc.name)):
                self.problems.append(GeometryProblem(item.link, item.kind, uri, str(exc)))
            return
        except FileNotFoundError:
            self.problems.append(GeometryProblem(item.link, item.kind, uri, "file not found"))
            return
        except RobomodelError as exc:
            self.problems.append(GeometryProblem(item.link, item.kind, uri, str(exc)))
            return
        except Exception as exc:  # one unreadable mesh never stops the ones after it
            message = f"{type(exc).__name__}: {exc}"
            self.problems.append(GeometryProblem(item.link, item.kind, uri, message))
            return
        scale = tuple(float(s) for s in item.geometry.scale or (1.0, 1.0, 1.0))
        with self._lock:
            if self._removed:
                return
            for j, part in enumerate(parts):
                name = f"{item.node}/m{j}"
                self.mesh_nodes.append(name)
                if part.glb is not None:
                    # A textured part is drawn with its texture, as RViz keeps a mesh's own
                    # materials; Alpha does not apply to it (no leaf).
                    self.scene.add_glb(name, part.glb, scale=scale, **_NO_SHADOWS)
                    continue
                # RViz: a mesh's own material wins; the URDF colour fills meshes without one.
                color = part.rgba or item.rgba or DEFAULT_RGBA
                handle = self.scene.add_mesh_simple(
                    name,
                    part.vertices,
                    part.faces,
                    color=rgb255(color),
                    opacity=self._opacity(color),
                    scale=scale,
                    side="double",
                    **_NO_SHADOWS,
                )
                self._leaves.append(_Leaf(handle, color))

    def _substitute(self, item: _PendingMesh, package: str) -> bool:
        """Draw ``item``'s link's primitive collision geometry as its visual (see the module
        docstring); False when the link has none. Once per link."""
        if any(link == item.link for _, link in self.substituted):
            self.substituted.append((package, item.link))
            return True
        link = self.robot.link(item.link)
        primitives = [c for c in link.collisions if not isinstance(c.geometry, Mesh)]
        if not primitives:
            return False
        link_node = item.node.rsplit("/", 1)[0]
        with self._lock:
            if self._removed:
                return True
            for k, collision in enumerate(primitives):
                self._add_geometry(
                    f"{link_node}/s{k}", link.name, "visual", collision.geometry,
                    collision.origin, item.rgba,
                )  # fmt: skip
        self.substituted.append((package, item.link))
        return True

    @property
    def pending_meshes(self) -> int:
        """Meshes not drawn yet: queued, or being read and added."""
        with self._lock:
            return len(self._pending) + self._loading

    # -- display options ------------------------------------------------------------------------
    def _opacity(self, rgba: Rgba) -> float | None:
        value = self.alpha * rgba[3]
        return None if value >= 0.999 else max(value, 0.0)

    def set_alpha(self, alpha: float) -> None:
        """RViz's Alpha: scales every geometry's own alpha."""
        self.alpha = alpha
        with self._lock:
            for leaf in self._leaves:
                leaf.handle.opacity = self._opacity(leaf.rgba)

    def set_shown(self, shown: bool) -> None:
        """Whether the robot is drawn at all (a RobotModel display that describes it is
        enabled); its links keep their own visibility below."""
        self.shown = shown
        if self._root is not None:
            self._root.visible = shown

    def set_visual_enabled(self, enabled: bool) -> None:
        self.show_visual = enabled
        for group in self._groups["visual"]:
            group.visible = enabled

    def set_collision_enabled(self, enabled: bool) -> None:
        self.show_collision = enabled
        for group in self._groups["collision"]:
            group.visible = enabled
        if enabled:
            with self._lock:
                self._pending.extend(self._deferred)
                self._deferred.clear()
            self.load_meshes()

    # -- poses --------------------------------------------------------------------------------
    def set_poses(
        self, wxyz: NDArray[np.float64], xyz: NDArray[np.float64], visible: NDArray[np.bool_]
    ) -> int:
        """Pose every link in the fixed frame; send only what changed. Returns links sent.

        Args:
            wxyz: Shape (n_links, 4), in :attr:`link_names` order.
            xyz: Shape (n_links, 3) [m].
            visible: Shape (n_links,): False for links with no transform to the fixed frame.
        """
        # Orientation and position are separate viser messages (each ~15 us to queue and send):
        # send each only when it changed, e.g. a link turning about its own origin sends one.
        turned = np.abs(wxyz - self._last_wxyz).max(axis=1, initial=0.0) > _ROTATION_TOL
        shifted = np.abs(xyz - self._last_xyz).max(axis=1, initial=0.0) > _POSITION_TOL_M
        new = np.isnan(self._last_xyz[:, 0])
        turned = (turned | new) & visible
        shifted = (shifted | new) & visible
        moved = turned | shifted
        shown = visible != self._last_visible
        wxyz_rows, xyz_rows = wxyz.tolist(), xyz.tolist()  # floats, not numpy scalars
        turned_rows, shifted_rows = turned.tolist(), shifted.tolist()
        for k in np.flatnonzero(moved).tolist():
            write_pose(
                self.scene,
                self._links[k],
                wxyz_rows[k] if turned_rows[k] else None,
                xyz_rows[k] if shifted_rows[k] else None,
            )
        self._last_wxyz[turned] = wxyz[turned]
        self._last_xyz[shifted] = xyz[shifted]
        for i in np.flatnonzero(shown):
            self._links[i].visible = bool(visible[i])
        self._last_visible = visible.copy()
        return int(moved.sum())

    def remove(self) -> None:
        """Take the robot out of the scene."""
        with self._lock:
            self._removed = True
            self._pending.clear()
        self.scene.remove_by_name(self.root)
