"""The Displays panel on a running viewer (its manager, the context displays get, the timer),
and the displays of its RViz config: opened into the panel, saved from it."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import replace
from pathlib import Path
from typing import Any

from robomodel.errors import RobomodelError
from robomodel.viewer.displays.base import (
    Display,
    DisplayContext,
    DisplayStatus,
    FrameLookup,
    display_class,
    is_rviz_display,
)
from robomodel.viewer.displays.follow import GraphFollower
from robomodel.viewer.displays.manager import DisplayManager
from robomodel.viewer.displays.panel import DisplaysPanel
from robomodel.viewer.displays.robot_model import show_robots, topic_name
from robomodel.viewer.displays.rviz_io import display_entry, display_values
from robomodel.viewer.meshes import resolve_mesh_uri
from robomodel.viewer.rviz_document import RvizDocument
from robomodel.viewer.rviz_model import RvizConfig, RvizDialect, RvizDisplay
from robomodel.viewer.tools.base import BusWorker

__all__ = ["MissingDisplay", "attach_displays", "config_with_displays", "open_config_displays"]

_DRAW_PERIOD_S = 0.1  # RViz updates displays every frame; 10 Hz keeps the page's load low


def attach_displays(viewer: Any, node: Any) -> DisplaysPanel:
    """The Displays folder of ``viewer`` (``viewer.server``, ``.buffer``, ``.meshes``,
    ``.options``, ``.fixed_frame``, ``._post``), drawing on ``node``'s timer (loop thread);
    with the rqt tools and no config file, its ``follower`` adds displays for the graph's
    scans and odometry (:mod:`~robomodel.viewer.displays.follow`)."""
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
        view_wxyz=_track_view(viewer.server),
        robots=lambda: viewer.sessions,
        clients=lambda: tuple(viewer.server.get_clients().values()),
        frame_rate_hz=lambda: float(viewer.frame_rate_hz),
    )
    manager = DisplayManager(context, node, viewer.buffer)
    folder = getattr(getattr(viewer, "options_panel", None), "displays_folder", None)
    panel = DisplaysPanel(
        viewer.server.gui, manager, viewer._post, BusWorker(node.context), folder=folder
    )
    document = getattr(viewer.options, "rviz", None)
    if getattr(viewer.options, "tools", False) and (document is None or document.missing):
        panel.follower = GraphFollower(panel)  # no config: the graph's scans and odometry
        manager.listeners.append(panel.follower)
    manager.listeners.append(lambda: show_robots(manager.displays, viewer.sessions))
    node.create_timer(_DRAW_PERIOD_S, manager.update)
    return panel


def _track_view(server: Any) -> Callable[[], tuple[float, float, float, float] | None]:
    """The orientation of the page camera that moved last (viser calls camera updates on its
    own thread; the tuple is swapped whole, so a reader sees one camera's)."""
    latest: list[tuple[float, float, float, float] | None] = [None]

    def moved(camera: Any) -> None:
        w, x, y, z = (float(v) for v in camera.wxyz)
        latest[0] = (w, x, y, z)

    def connected(client: Any) -> None:
        client.camera.on_update(moved)

    server.on_client_connect(connected)
    return lambda: latest[0]


class MissingDisplay(Display):
    """A display of a class robomodel lacks: listed with RViz's status for a plugin it cannot
    load, its settings kept for saving."""

    def __init__(self, entry: RvizDisplay, context: DisplayContext) -> None:
        super().__init__(entry.name, context, enabled=entry.enabled)
        self.config_entry = entry

    def draw(self, lookup: FrameLookup) -> DisplayStatus:
        # rviz::FailedDisplay's description
        return DisplayStatus.error(
            f"The class required for this display, '{self.config_entry.class_name}', could "
            "not be loaded."
        )


def open_config_displays(
    panel: DisplaysPanel, document: RvizDocument, robots: Sequence[Any] = ()
) -> list[str]:
    """Add the document's displays to ``panel`` (before the loop runs, or on it); one line
    per option value that could not be taken. Without a config file (``document.missing``:
    RViz's defaults), the defaults' RobotModel becomes one per robot of ``robots`` (the
    viewer's sessions), each on its robot's description topic: a user who views files
    without a config sees every robot."""
    problems: list[str] = []
    for entry in document.config.displays:
        if document.missing and entry.kind == "RobotModel" and robots:
            problems += _robot_models(panel, document, entry, robots)
            continue
        if not is_rviz_display(entry.class_name):
            missing = MissingDisplay(entry, panel.manager.context)
            missing.name = panel.manager.unique_name(entry.name)
            panel.manager.displays.append(missing)
            panel.add_row(missing)
            continue
        cls = display_class(entry.class_name)
        values, skipped = display_values(cls, entry.settings, document.dialect)
        problems += [f"{entry.name}: {line}" for line in skipped]
        display = panel.add(entry.class_name, name=entry.name, values=values, enabled=entry.enabled)  # fmt: skip
        if display is not None:
            display.config_entry = entry
    return problems


def _robot_models(
    panel: DisplaysPanel, document: RvizDocument, entry: RvizDisplay, robots: Sequence[Any]
) -> list[str]:
    """The defaults' RobotModel ``entry`` as one display per robot (the first is the entry)."""
    cls = display_class(entry.class_name)
    values, skipped = display_values(cls, entry.settings, document.dialect)
    for number, robot in enumerate(robots):
        topic = robot.description_topic
        if topic_name(str(values.get("Description Topic", ""))) != topic:
            values["Description Topic"] = topic
        values["TF Prefix"] = robot.prefix.strip("/")
        display = panel.add(entry.class_name, name=entry.name, values=values, enabled=entry.enabled)  # fmt: skip
        if display is not None and number == 0:
            display.config_entry = entry
    return [f"{entry.name}: {line}" for line in skipped]


def config_with_displays(
    displays: list[Display], config: RvizConfig, dialect: RvizDialect
) -> tuple[RvizConfig, Callable[[], None]]:
    """``config`` with the panel's displays in place of those it was read with, new ones at
    the end; and what to call once it is saved (the displays then remember the entries
    written)."""
    by_entry = {id(d.config_entry): d for d in displays if d.config_entry is not None}
    out: list[RvizDisplay] = []
    written: list[tuple[Display, RvizDisplay]] = []
    for entry in config.displays:
        display = by_entry.get(id(entry))
        if display is None:
            continue  # a display removed in the page
        out.append(_entry(display, dialect, entry))
        written.append((display, out[-1]))
    for display in displays:
        if display.config_entry is None:
            out.append(_entry(display, dialect, None))
            written.append((display, out[-1]))

    def saved() -> None:
        for display, entry in written:
            display.config_entry = entry

    return replace(config, displays=tuple(out)), saved


def _entry(display: Display, dialect: RvizDialect, base: RvizDisplay | None) -> RvizDisplay:
    if isinstance(display, MissingDisplay):
        entry = display.config_entry
        return RvizDisplay(entry.class_name, display.name, display.enabled, entry.settings)
    return display_entry(display, dialect, base)
