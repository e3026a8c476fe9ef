"""Parameters (rqt_reconfigure / dynamic_reconfigure): edit a node's parameters live.

A node is picked from the graph, its parameters are listed through its rcl_interfaces
parameter services (``list_parameters`` then ``get_parameters``, as ``robomodel param`` does;
real ROS 2 nodes on the bus answer too) and shown as number boxes, checkboxes or
text boxes (arrays as YAML). Each edit is one ``set``; a refusal puts the old value back and
shows the node's reason.
"""

from __future__ import annotations

from typing import Any

from robomodel.errors import RobomodelError
from robomodel.runtime.param_client import ParameterClient
from robomodel.runtime.params import SetResult, parameter_type_name, parse_parameter_value
from robomodel.viewer.limits import MAX_PARAMETERS_SHOWN
from robomodel.viewer.markup import code, md, safe_markdown
from robomodel.viewer.tools.base import ToolContext

__all__ = ["ParameterTool"]

_NONE = "(choose a node)"


class ParameterTool:
    """The "Parameters" folder's controls, built inside ``parent``."""

    def __init__(self, tools: ToolContext, parent: Any) -> None:
        self.tools = tools
        self._parent = parent  # the folder the node's controls go in (built on another thread)
        self.gui = tools.server.gui
        self.node_dropdown = self.gui.add_dropdown("Node", (_NONE,), initial_value=_NONE)
        refresh = self.gui.add_button("Reload parameters")
        self.result = safe_markdown(self.gui)
        self._folder: Any = None
        self.controls: dict[str, Any] = {}
        self.values: dict[str, Any] = {}
        self.node_name = ""
        self.sets = 0
        self.node_dropdown.on_update(lambda _e: self.load(str(self.node_dropdown.value)))
        refresh.on_click(lambda _e: self.load(str(self.node_dropdown.value)))

    def update_nodes(self, nodes: set[str]) -> None:
        """New node names from the graph (any thread)."""
        options = (_NONE, *sorted(nodes))
        if tuple(self.node_dropdown.options) != options:
            current = self.node_dropdown.value
            self.node_dropdown.options = options
            self.node_dropdown.value = current if current in options else _NONE

    def load(self, node: str) -> None:
        """List ``node``'s parameters and build their controls (queried on the bus worker)."""
        if node == _NONE:
            return

        def job() -> None:
            try:
                client = self._client(node)
                names = self.tools.bus.query(client.list_names)
                values = self.tools.bus.query(lambda: client.get(names)) if names else {}
            except RobomodelError as exc:
                self.result.content = md("**{}:** {}", node, exc)
                return
            self._build(node, values)

        self.tools.bus.submit(job)

    def _client(self, node: str) -> ParameterClient:
        return ParameterClient(self.tools.node.context, node)

    def _build(self, node: str, values: dict[str, Any]) -> None:
        if self._folder is not None:
            self._folder.remove()
        self.controls = {}
        self.node_name, self.values = node, dict(values)
        with self._parent:
            self._folder = self.gui.add_folder(node)
        shown = sorted(values.items())[:MAX_PARAMETERS_SHOWN]
        with self._folder:
            for name, value in shown:
                self.controls[name] = self._control(name, value)
        if len(shown) < len(values):
            self.result.content = md(
                "{} parameter(s) of {}; the first {} shown", len(values), code(node), len(shown)
            )
        else:
            self.result.content = md("{} parameter(s) of {}", len(values), code(node))

    def _control(self, name: str, value: Any) -> Any:
        kind = parameter_type_name(value)
        if kind == "bool":
            control = self.gui.add_checkbox(name, value)
        elif kind in ("integer", "double"):
            control = self.gui.add_number(name, value, step=1 if kind == "integer" else 0.001)
        else:
            control = self.gui.add_text(name, value if kind == "string" else str(value))
        control.on_update(lambda event: self._edited(name, kind, event))
        return control

    def _edited(self, name: str, kind: str, event: Any) -> None:
        if event.client is None:  # set by the program (a refusal put the old value back)
            return
        raw = self.controls[name].value
        value: Any = raw
        if kind.endswith("array") or kind == "array":
            value = parse_parameter_value(str(raw))
        node = self.node_name
        self.tools.bus.submit(lambda: self.set(node, name, value))

    def set(self, node: str, name: str, value: Any) -> bool:
        """Set one parameter (bus worker thread); show the outcome, revert on refusal."""
        client = self._client(node)
        try:
            result = self.tools.bus.query(lambda: client.set({name: value}))[0]
        except (RobomodelError, IndexError) as exc:
            result = SetResult(False, str(exc) or "no answer")
        self.sets += 1
        if result.successful:
            self.values[name] = value
            self.result.content = md("{} set to {}", code(name), code(value))
            return True
        self.result.content = md("**refused:** {}: {}", code(name), result.reason)
        control = self.controls.get(name)
        old = self.values.get(name)
        if control is not None and node == self.node_name:
            control.value = old if isinstance(old, (bool, int, float, str)) else str(old)
        return False
