"""The viewer: a viser server, the robots' sessions, and the loop that keeps the page current.

One thread spins the runtime context (robot_state_publisher, joint_state_publisher, the TF
listener) and, whenever /tf or /tf_static brought something new or a display option changed,
looks every link up in the fixed frame and sends the poses that changed to the browsers in one
atomic, immediately flushed batch. The same thread polls the description files for changes.
GUI callbacks (viser's threads) only post work to that thread, so the nodes are never touched
from two threads.
"""

from __future__ import annotations

import contextlib
import io
import logging
import os
import threading
import time
from collections.abc import Callable
from typing import Any

from robomodel.errors import RobomodelError
from robomodel.runtime.context import Context
from robomodel.runtime.msg import TFMessage
from robomodel.runtime.node import Node
from robomodel.runtime.qos import Durability, QoSProfile
from robomodel.runtime.tf_listener import TransformListener
from robomodel.viewer._deps import import_viser
from robomodel.viewer.config_panel import attach_rviz
from robomodel.viewer.displays.attach import attach_displays
from robomodel.viewer.displays.robot_model import show_robots
from robomodel.viewer.displays.tf import TFDisplay
from robomodel.viewer.layout import place_camera, session_namespace
from robomodel.viewer.layout import zero_pose_extent_m as zero_pose_extent_m
from robomodel.viewer.link_poses import append_other_frames
from robomodel.viewer.markup import Markup
from robomodel.viewer.meshes import MeshCache
from robomodel.viewer.options import ViewerOptions
from robomodel.viewer.options_panel import OptionsPanel
from robomodel.viewer.pacing import page_behind
from robomodel.viewer.placement import Placement
from robomodel.viewer.ports import ensure_port_free
from robomodel.viewer.rviz_apply import apply_rviz_view
from robomodel.viewer.scenery import SceneryDisplay
from robomodel.viewer.session import DisplayOptions, LoadFailure, RobotSession
from robomodel.viewer.status import viewer_status
from robomodel.viewer.topic_robots import TopicRobots

__all__ = ["Viewer", "ViewerOptions"]

log = logging.getLogger("robomodel.viewer")
# How often the loop looks whether a page that was behind has taken the last update.
_PAGE_POLL_S = 0.005

WAIT_SLICE_S = 0.2  # how soon the main thread looks at a signal another thread received


class Viewer:
    """``robomodel view``: serve the robots on a web page until :meth:`close`."""

    def __init__(self, options: ViewerOptions) -> None:
        # No sources is RViz's empty start: a RobotModel display added (or the config's)
        # brings a robot (robomodel.viewer.topic_robots).
        for source in options.sources:
            if source.topic is None and not os.path.isfile(source.path):
                raise RobomodelError(f"cannot read '{source.path}': no such file")
        if not 1.0 <= options.frame_rate_hz <= 1000.0:
            raise RobomodelError(f"frame rate must be 1..1000 Hz, got {options.frame_rate_hz}")
        self.options = options
        self.frame_rate_hz = options.frame_rate_hz  # Global Options > Frame Rate changes it
        count = len(options.sources)
        self.sessions = [
            RobotSession(
                i,
                source,
                index=options.package_index,
                namespace=session_namespace(source, i, count),
                external=options.external,
                state_publisher=options.state_publisher,
            )
            for i, source in enumerate(options.sources)
        ]
        self.display_options = DisplayOptions()
        self.meshes = MeshCache()
        self.updates_sent = 0
        # viser's ids of the first and last message of the last update, and when it went out
        self._last_push_ids: tuple[int, int] | None = None
        self._last_push_s = 0.0
        self.reloads = 0
        self.server: Any = None
        self.context: Context | None = None
        self.buffer: Any = None
        self._stop = threading.Event()
        self._dirty = True
        self._threads: list[threading.Thread] = []
        self.placement = Placement()  # what the last scene updates found, robot by robot
        self._status_text = ""
        self.status_note = Markup("")  # appended to the Status (e.g. RViz displays not supported)
        self._frame_options: tuple[str, ...] = ()
        rviz = options.rviz.settings if options.rviz is not None else None
        self.fixed_frame = options.fixed_frame or (rviz.fixed_frame if rviz else None) or ""
        self.meshes_ready = threading.Event()
        self.tools: Any = None
        self.displays: Any = None  # the DisplayManager (loop thread), once started
        self.displays_panel: Any = None
        self._node: Node | None = None
        self.scenery: SceneryDisplay | None = None
        self.topic_robots: TopicRobots | None = None  # robots RobotModel displays load

    # -- lifecycle ----------------------------------------------------------------------------
    @property
    def url(self) -> str:
        port = self.server.get_port() if self.server is not None else self.options.port
        host = self.options.host
        return f"http://{'[' + host + ']' if ':' in host else host}:{port}"

    def start(self) -> None:
        """Load the robots, start the nodes and the server; return once the page is served."""
        ensure_port_free(self.options.host, self.options.port)
        viser = import_viser()
        for session in self.sessions:
            session.try_load()
        if not self.fixed_frame:
            roots = [s.root_frame for s in self.sessions if s.root_frame]
            self.fixed_frame = roots[0] if roots else "base_link"
            self._guess_fixed = not roots  # a description from a topic: its root, once loaded
        opts = self.options
        self.context = Context(
            opts.bus,
            domain_id=opts.domain_id,
            connect=opts.connect,
            listen=opts.listen,
            master=opts.master,
        )
        node = self.context.create_node("robomodel_viewer")
        self.buffer = TransformListener(node).buffer
        node.create_subscription(TFMessage, "/tf", self._on_tf, 100)
        node.create_subscription(
            TFMessage, "/tf_static", self._on_tf, QoSProfile(100, Durability.TRANSIENT_LOCAL)
        )
        for session in self.sessions:
            session.start_nodes(self.context, node)
        self._node = node
        with contextlib.redirect_stdout(io.StringIO()):  # viser prints its own banner
            self.server = viser.ViserServer(
                host=opts.host, port=opts.port, label="robomodel view", verbose=False
            )
        robots = self.topic_robots = TopicRobots(self, node, self._forget)
        self._build_gui()
        # before show_robots: a RobotModel naming a topic no robot is described on loads one
        self.displays.listeners.insert(0, lambda: robots.sync(self.displays.displays))
        self._place_camera()
        if opts.scenery:
            self.scenery = SceneryDisplay(self.server.scene, opts.scenery)
        for session in self.sessions:
            session.build_display(
                self.server.scene, self.meshes, self.display_options, load_meshes=False
            )
            session.build_panel(self.server.gui, self._post)
            session.publish_bodies()
        show_robots(self.displays.displays, self.sessions)  # as the config's RobotModels say
        if opts.tools:
            self._build_tools(node)
        self._spawn(self._loop, "robomodel-view-loop")
        self._spawn(self._load_meshes, "robomodel-view-meshes")

    def _place_camera(self) -> None:
        """RViz's orbit view, far enough to see the first robot (see :func:`place_camera`)."""
        robot = next((s.robot for s in self.sessions if s.robot is not None), None)
        place_camera(self.server, robot, len(self.sessions), self.options.scenery)
        if self.options.rviz is not None:  # the -d file's Orbit view, as RViz opens it
            apply_rviz_view(self.server, self.options.rviz)

    def _spawn(self, target: Callable[[], None], name: str) -> None:
        thread = threading.Thread(target=target, name=name, daemon=True)
        self._threads.append(thread)
        thread.start()

    def wait(self, timeout_s: float | None = None) -> None:
        """Block until :meth:`close` (or ``timeout_s``), in slices of ``WAIT_SLICE_S``: the
        kernel may hand Ctrl-C's SIGINT to any thread of the process (a Zenoh or viser one),
        and Python raises KeyboardInterrupt only when its main thread next runs, which an
        endless wait never would."""
        deadline = None if timeout_s is None else time.monotonic() + timeout_s
        while not self._stop.is_set():
            remaining = WAIT_SLICE_S if deadline is None else deadline - time.monotonic()
            if remaining <= 0:
                return
            self._stop.wait(min(remaining, WAIT_SLICE_S))

    def close(self) -> None:
        if self.tools is not None:
            self.tools.close()
        if self.topic_robots is not None:
            self.topic_robots.close()
        if self.displays_panel is not None:
            self.displays_panel.close()
        self._stop.set()
        for thread in self._threads:
            if thread is not threading.current_thread():
                thread.join(timeout=5)
        if self.server is not None:
            with contextlib.redirect_stdout(io.StringIO()):  # viser's "Server stopped"
                self.server.stop()
        if self.context is not None:
            self.context.shutdown()

    def __enter__(self) -> Viewer:
        self.start()
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    # -- GUI ------------------------------------------------------------------------------------
    def _post(self, work: Callable[[], object]) -> None:
        """Run ``work`` on the loop thread (the only one that touches the nodes)."""
        assert self.context is not None

        def run() -> None:
            work()
            self._dirty = True

        self.context.executor.post(run)

    def _build_gui(self) -> None:
        panel = OptionsPanel(
            self.server,
            fixed_frame=self.fixed_frame,
            post=self._post,
            on_fixed_frame=lambda frame: setattr(self, "fixed_frame", frame),
            frame_rate_hz=self.frame_rate_hz,
            on_frame_rate=lambda hz: setattr(self, "frame_rate_hz", hz),
        )
        self.options_panel = panel
        self.status = panel.status
        self.fixed_dropdown = panel.fixed_dropdown
        self.frame_rate_number = panel.frame_rate
        self.displays_panel = attach_displays(self, self._node)
        self.displays = self.displays_panel.manager
        self.config_panel = attach_rviz(self, panel)

    def _build_tools(self, node: Node) -> None:
        from robomodel.viewer.tools import BusWorker, ToolContext, ToolsPanel

        assert self.context is not None
        self.tools = ToolsPanel(
            ToolContext(
                server=self.server,
                node=node,
                post=self._post,
                bus=BusWorker(self.context),
                buffer=self.buffer,
                fixed_frame=lambda: self.fixed_frame,
            )
        )

    # -- the loop -------------------------------------------------------------------------------
    def _forget(self, number: int) -> None:
        """Drop what was kept about robot ``number`` (removed from the viewer)."""
        self.placement.forget(number)
        self._dirty = True

    def _on_tf(self, _msg: TFMessage) -> None:
        self._dirty = True

    def _load_meshes(self) -> None:
        for session in self.sessions:
            if session.display is not None:
                session.display.load_meshes()
        self.meshes_ready.set()
        self._dirty = True

    def _loop(self) -> None:
        while not self._stop.is_set():
            try:
                self._run_loop()
            except Exception:  # the page must outlive any one bad update
                log.exception("viewer update failed; going on")
                time.sleep(0.1)

    def _run_loop(self) -> None:
        assert self.context is not None
        next_reload = next_status = next_bodies = next_push = 0.0
        behind = False
        while not self._stop.is_set():
            # Wait for a message (spin_once returns when one is handled) or the first thing due:
            # an idle scene costs a wake-up per deadline, not one every few milliseconds.
            now = time.monotonic()
            push_s = max(next_push, now if self._dirty else self.placement.due_s)
            due_s = min(next_reload, next_status, next_bodies, push_s)
            # A slider's value (queued by viser's thread, which does not wake this loop) is
            # applied within one frame, as when it waited for the next update.
            longest_s = 1.0 / self.frame_rate_hz
            wait_s = _PAGE_POLL_S if behind else min(max(0.0, due_s - now), longest_s)
            self.context.spin_once(wait_s)
            now = time.monotonic()
            if now >= next_push:
                # Slider values are applied when a scene update is due, not at every turn: a
                # joint state (and its /tf through robot_state_publisher) that no update would
                # show is not computed, so a drag costs one message per update at most.
                for session in self.sessions:
                    if session.apply_queued():
                        self.context.spin_once(0.0)  # robot_state_publisher -> /tf -> buffer
            if now >= next_reload:
                next_reload = now + self.options.reload_period_s
                self._check_reload()
            due = (
                self._dirty or now >= self.placement.due_s
            )  # TF moved, or an Update Interval passed
            on_time = due and now >= next_push
            behind = on_time and self._page_behind(now)
            if on_time and not behind:
                # On the schedule, not from now: the loop's own latency does not lower the rate.
                next_push = max(next_push + 1.0 / self.frame_rate_hz, now)
                self._dirty = False
                self._push()
            if now >= next_status:
                next_status = now + 0.25
                self._refresh_scenery()
                self._refresh_frames()
                self._refresh_status()
                if any(isinstance(d, TFDisplay) and d.fading() for d in self.displays.displays):
                    self._dirty = True  # an old frame greys and fades though no /tf arrives
            if now >= next_bodies:
                # Republished like joint_state_publisher's joint states (10 Hz), so that lookups
                # through a floating joint never need data older than the TF cache holds.
                next_bodies = now + 0.1
                for session in self.sessions:
                    session.publish_bodies()

    def _check_reload(self) -> None:
        for session in self.sessions:
            if not session.watcher.changed():
                continue
            if session.try_load():
                try:
                    session.apply_reload()
                except RobomodelError as exc:
                    session.failure = LoadFailure.from_error(exc)
                    continue
                session.build_display(
                    self.server.scene, self.meshes, self.display_options, load_meshes=True
                )
                session.build_panel(self.server.gui, self._post)
                show_robots(self.displays.displays, self.sessions)
                self.placement.extent_m.pop(session.number, None)
                self.reloads += 1
            self._dirty = True
            self._refresh_status()

    def _broadcast_buffer(self) -> Any:
        """viser's outgoing broadcast buffer (1.1's internals), or None if it differs."""
        buffer = getattr(getattr(self.server, "_websock_server", None), "_broadcast_buffer", None)
        ok = hasattr(buffer, "generator_cursors") and hasattr(buffer, "message_counter")
        return buffer if ok else None

    def _page_behind(self, now: float) -> bool:
        """Whether a page still waits for the previous update (see :func:`page_behind`)."""
        return page_behind(self._broadcast_buffer(), self._last_push_ids, self._last_push_s, now)

    def _push(self) -> None:
        """Send the poses that changed, as one atomic batch, flushed immediately."""
        buffer = self._broadcast_buffer()
        first_id = buffer.message_counter if buffer is not None else 0
        with self.server.atomic():
            placed = self.placement.place(
                self.sessions, self.buffer, self.fixed_frame, time.monotonic()
            )
            append_other_frames(self.buffer, self.fixed_frame, self.sessions, placed.frames,
                                placed.wxyzs, placed.xyzs, placed.shown)  # fmt: skip
            if self.scenery is not None:
                self.scenery.update(self.buffer, self.fixed_frame)
            placed.show_in(self.displays.displays, self.buffer)
        self.server.flush()
        self.updates_sent += 1
        if buffer is not None:
            self._last_push_ids = (first_id, buffer.message_counter - 1)
            self._last_push_s = time.monotonic()

    def _refresh_scenery(self) -> None:
        """Redraw the scenery when its source has other shapes (a model spawned or deleted)."""
        source = self.options.scenery_source
        if source is None:
            return
        shapes = source()
        if shapes == (self.scenery.shapes if self.scenery is not None else ()):
            return
        if self.scenery is not None:
            self.scenery.remove()
        self.scenery = SceneryDisplay(self.server.scene, shapes) if shapes else None
        self._dirty = True

    def _refresh_frames(self) -> None:
        roots = [s.root_frame for s in self.sessions if s.root_frame]
        if getattr(self, "_guess_fixed", False) and roots:
            self.fixed_frame, self._guess_fixed = roots[0], False
        stale = set().union(*(s.stale_frames for s in self.sessions))
        frames = {f for f in self.buffer.frames if f not in stale}
        for session in self.sessions:
            frames.update(session.link_frames())
        frames.add(self.fixed_frame)
        options = tuple(sorted(frames))
        if options != self._frame_options:
            self._frame_options = options
            self.fixed_dropdown.options = options
            self.fixed_dropdown.value = self.fixed_frame

    def _refresh_status(self) -> None:
        text = Markup(
            viewer_status(
                self.sessions,
                self.buffer,
                self.fixed_frame,
                self.placement.missing,
                self.placement.beside,
            )
            + self.status_note
        )
        if text != self._status_text:
            self._status_text = text
            self.status.content = text
