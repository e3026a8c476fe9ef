"""The page's Displays folder: RViz's Displays tree and its "Add" dialog.

"Add display" adds one by type (every registered display class) or by topic (the live
graph's topics with a type some display takes, as RViz's "By topic" tab). Each display is a
folder named as the display, holding its status line, Enabled, Name, its options (from the
display's option table, with RViz's names) and Remove. Changes are posted to the viewer's loop
thread, which owns the displays; the status lines are refreshed after each update there.
"""

from __future__ import annotations

import logging
import threading
from collections.abc import Callable, Mapping
from typing import Any

from robomodel.errors import RobomodelError
from robomodel.viewer.displays.base import (
    Display,
    Option,
    OptionKind,
    StatusLevel,
    color_rgb,
    display_classes,
)
from robomodel.viewer.displays.manager import DisplayManager
from robomodel.viewer.markup import Markup, md, safe_markdown
from robomodel.viewer.tools.base import BusWorker

__all__ = ["DisplaysPanel", "status_markdown", "topic_choices"]

log = logging.getLogger("robomodel.viewer")

_CHOOSE = "(choose)"
_GRAPH_PERIOD_S = 1.0
_MARK = {StatusLevel.OK: "✓ Ok", StatusLevel.WARN: "⚠ Warn", StatusLevel.ERROR: "✗ Error"}


def status_markdown(display: Display) -> Markup:
    """The display's status line as the panel shows it."""
    status = display.status
    return md("**Status: {}** {}", Markup(_MARK[status.level]), status.text)


def topic_choices(topics: Mapping[str, frozenset[str]]) -> dict[str, tuple[str, str]]:
    """ "Add by topic" entries: ``"<topic> (<Display>)"`` -> (display class, topic), for every
    topic whose type a display takes."""
    by_type: dict[str, list[str]] = {}
    for name, cls in display_classes().items():
        for type_name in cls.message_types:
            by_type.setdefault(type_name, []).append(name)
    out: dict[str, tuple[str, str]] = {}
    for topic in sorted(topics):
        for type_name in sorted(topics[topic]):
            for class_name in by_type.get(type_name, ()):
                out[f"{topic} ({class_name})"] = (class_name, topic)
    return out


def _entry_on(value: Any) -> bool:
    """A MAP option's entry as a checkbox: a bool, or RViz's ``{Value: bool}`` (TF's Frames)."""
    if isinstance(value, Mapping):
        return bool(value.get("Value", True))
    return bool(value)


class _Row:
    """One display's folder and controls."""

    def __init__(self, panel: DisplaysPanel, display: Display) -> None:
        self.display = display
        gui, post = panel.gui, panel.post
        self._post = post
        self.namespaces: dict[str, Any] = {}
        self._shown: dict[str, bool] = {}  # the option's value last written to each box
        with panel.folder:
            self.folder = gui.add_folder(display.name, expand_by_default=False)
        with self.folder:
            self.status = safe_markdown(gui, status_markdown(display))
            self.enabled = gui.add_checkbox("Enabled", display.enabled)
            self.name = gui.add_text("Name", display.name)
            self.controls = {o.name: self._control(gui, o) for o in display.options}
            display.build_panel(gui)
            self.remove = gui.add_button("Remove", color="red")
        display.build_dock(gui)  # at the panel's top level, not in the Displays tree
        self.enabled.on_update(lambda _e: post(lambda: display.set_enabled(bool(self.enabled.value))))  # fmt: skip
        self.name.on_update(lambda _e: post(lambda: panel.rename(self, str(self.name.value))))
        self.remove.on_click(lambda _e: post(lambda: panel.remove(self)))

    def _control(self, gui: Any, option: Option) -> Any:
        value = self.display.option(option.name)
        kind = option.kind
        if kind is OptionKind.BOOL:
            control = gui.add_checkbox(option.name, value, hint=option.help or None)
        elif kind in (OptionKind.INT, OptionKind.FLOAT):
            step = 1 if kind is OptionKind.INT else 0.01
            control = gui.add_number(option.name, value, min=option.minimum, max=option.maximum, step=step, hint=option.help or None)  # fmt: skip
        elif kind is OptionKind.CHOICE:
            control = gui.add_dropdown(option.name, option.choices, initial_value=value)
        elif kind is OptionKind.COLOR:
            control = gui.add_rgb(option.name, color_rgb(value))
        elif kind is OptionKind.MAP:
            return gui.add_folder(option.name, expand_by_default=False)
        else:
            control = gui.add_text(option.name, value, hint=option.help or None)
        control.on_update(lambda _e: self._changed(option, control.value))
        return control

    def _changed(self, option: Option, value: Any) -> None:
        self._post(lambda: self._set(option.name, value))

    def _set(self, name: str, value: Any) -> None:
        try:
            self.display.set_option(name, value)
        except RobomodelError as exc:
            self.status.content = md("**Status: ✗ Error** {}", exc)

    def refresh(self, gui: Any) -> None:
        """Status line and namespace checkboxes (loop thread, after an update)."""
        text = status_markdown(self.display)
        if self.status.content != text:
            self.status.content = text
        for option in self.display.options:
            if option.kind is OptionKind.MAP:
                self._refresh_map(gui, option.name)

    def _refresh_map(self, gui: Any, name: str) -> None:
        entries = self.display.map_entries(name)
        for key, value in entries.items():
            on = _entry_on(value)
            box = self.namespaces.get(key)
            if box is None:
                with self.controls[name]:
                    box = self.namespaces[key] = gui.add_checkbox(str(key) or "(empty)", bool(on))  # fmt: skip
                box.on_update(lambda _e, k=key, b=box: self._changed_map(name, k, bool(b.value)))
            elif bool(on) != self._shown.get(key):
                box.value = bool(on)  # its update callback sees the option's value: no change
            # Only a change of the option is written to the box: a box that merely differs may
            # hold a click whose callback has not run yet (viser sets the value first).
            self._shown[key] = bool(on)

    def _changed_map(self, name: str, key: str, on: bool) -> None:
        # A click, or this panel writing the option's value back (viser calls the callbacks
        # then too): only a value that differs from the option is the user's.
        if on == _entry_on(self.display.map_entries(name).get(key, True)):
            return

        def store() -> None:
            old = self.display.map_entries(name).get(key)
            value = {**old, "Value": on} if isinstance(old, Mapping) else on  # keep its form
            self._set(name, {**self.display.option(name), key: value})

        self._post(store)


class DisplaysPanel:
    """The Displays folder over a :class:`DisplayManager`.

    Args:
        gui: viser's GUI API.
        manager: The displays (loop thread).
        post: Runs a callable on the loop thread.
        bus: The worker that asks the graph for its topics (None: no "Add by topic" list).
        folder: The Displays folder to fill (None: a new one).
    """

    def __init__(
        self,
        gui: Any,
        manager: DisplayManager,
        post: Callable[[Callable[[], object]], None],
        bus: BusWorker | None = None,
        folder: Any = None,
    ) -> None:
        self.gui, self.manager, self.post, self.bus = gui, manager, post, bus
        self.rows: list[_Row] = []
        self.follower: Any = None  # adds displays for the graph's topics (displays/follow.py)
        self.topics: dict[str, frozenset[str]] = {}
        self._choices: dict[str, tuple[str, str]] = {}
        self.folder = gui.add_folder("Displays") if folder is None else folder
        with self.folder, gui.add_folder("Add display", expand_by_default=False):
            names = tuple(display_classes())
            self.type_dropdown = gui.add_dropdown("Display type", names, initial_value=names[0])  # fmt: skip
            self.add_type_button = gui.add_button("Add by type", icon="plus")
            self.topic_dropdown = gui.add_dropdown("Topic", (_CHOOSE,), initial_value=_CHOOSE)  # fmt: skip
            self.add_topic_button = gui.add_button("Add by topic", icon="plus")
            self.add_status = safe_markdown(gui)
        self.add_type_button.on_click(lambda _e: self._on_add_type())
        self.add_topic_button.on_click(lambda _e: self._on_add_topic())
        manager.listeners.append(self.refresh)
        self._stop = threading.Event()
        self._pending = threading.Event()
        if bus is not None:
            self._thread = threading.Thread(target=self._watch, name="robomodel-view-displays-graph", daemon=True)  # fmt: skip
            self._thread.start()

    # -- adding (GUI threads post; the rest runs on the loop thread) ---------------------------
    def _on_add_type(self) -> None:
        class_name = str(self.type_dropdown.value)
        self.post(lambda: self.add(class_name))

    def _on_add_topic(self) -> None:
        choice = self._choices.get(str(self.topic_dropdown.value))
        if choice is None:
            self.add_status.content = md("Choose a topic first")
            return
        class_name, topic = choice
        self.post(lambda: self.add(class_name, values={"Topic": topic}, name=topic))

    def add(self, class_name: str, *, name: str | None = None, values: Mapping[str, Any] | None = None, enabled: bool = True) -> Display | None:  # fmt: skip
        """Add a display and its folder (loop thread); None (and the reason shown) if it
        cannot be added."""
        try:
            display = self.manager.add(class_name, name, values, enabled=enabled)
        except RobomodelError as exc:
            self.add_status.content = md("**Not added**: {}", exc)
            return None
        self.add_status.content = md("Added {}", display.name)
        self.add_row(display)
        return display

    def add_row(self, display: Display) -> None:
        """The folder of a display the manager has (loop thread)."""
        self.rows.append(_Row(self, display))

    def remove(self, row: _Row) -> None:
        self.manager.remove(row.display)
        row.folder.remove()
        self.rows.remove(row)

    def rename(self, row: _Row, name: str) -> None:
        try:
            self.manager.rename(row.display, name)
        except RobomodelError as exc:
            row.status.content = md("**Status: ✗ Error** {}", exc)
            return
        row.folder.label = row.display.name

    def refresh(self) -> None:
        for row in self.rows:
            row.refresh(self.gui)

    # -- the graph (its own thread, queries on the bus worker) ---------------------------------
    def _watch(self) -> None:
        while not self._stop.is_set():
            if not self._pending.is_set() and self.bus is not None:
                self._pending.set()
                self.bus.submit(self.refresh_graph)
            self._stop.wait(_GRAPH_PERIOD_S)

    def refresh_graph(self) -> None:
        """Ask the bus for its topics (bus worker thread)."""
        try:
            assert self.bus is not None
            context = self.manager.node.context
            try:
                graph = self.bus.query(lambda: context.graph(timeout_s=0.5))
            except RobomodelError:  # a loop busy for seconds (a loaded machine): next round
                return
            self.topics = {name: frozenset(info.types) for name, info in graph.topics.items()}
            self._choices = topic_choices(self.topics)
            options = (_CHOOSE, *self._choices)
            if tuple(self.topic_dropdown.options) != options:
                current = self.topic_dropdown.value
                self.topic_dropdown.options = options
                self.topic_dropdown.value = current if current in options else _CHOOSE
        finally:
            self._pending.clear()

    def close(self) -> None:
        self._stop.set()
        if self.bus is not None:
            self._thread.join(timeout=5)
            self.bus.close()
