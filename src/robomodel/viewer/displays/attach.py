"""The Displays panel on a running viewer: its manager, the context displays get, the timer."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from robomodel.errors import RobomodelError
from robomodel.viewer.displays.base import DisplayContext
from robomodel.viewer.displays.manager import DisplayManager
from robomodel.viewer.displays.panel import DisplaysPanel
from robomodel.viewer.meshes import resolve_mesh_uri
from robomodel.viewer.tools.base import BusWorker

__all__ = ["attach_displays"]

_DRAW_PERIOD_S = 0.1  # RViz updates displays every frame; 10 Hz keeps the page's load low


def attach_displays(viewer: Any, node: Any) -> DisplaysPanel:
    """The Displays folder of ``viewer`` (``viewer.server``, ``.buffer``, ``.meshes``,
    ``.options``, ``.fixed_frame``, ``._post``), drawing on ``node``'s timer (loop thread)."""
    panel: DisplaysPanel | None = None

    def topic_types(topic: str) -> frozenset[str]:
        return panel.topics.get(topic, frozenset()) if panel is not None else frozenset()

    def load_mesh(uri: str) -> tuple[Any, ...]:
        path = resolve_mesh_uri(viewer.options.package_index, uri, Path.cwd())
        try:
            parts: tuple[Any, ...] = viewer.meshes.get(path)
        except FileNotFoundError:
            raise RobomodelError(f"mesh {uri}: no such file {path}") from None
        return parts

    context = DisplayContext(
        scene=viewer.server.scene,
        gui=viewer.server.gui,
        fixed_frame=lambda: viewer.fixed_frame,
        topic_types=topic_types,
        post=viewer._post,
        now_ns=lambda: node.get_clock().now_ns(),
        load_mesh=load_mesh,
    )
    manager = DisplayManager(context, node, viewer.buffer)
    panel = DisplaysPanel(viewer.server.gui, manager, viewer._post, BusWorker(node.context))
    node.create_timer(_DRAW_PERIOD_S, manager.update)
    return panel
