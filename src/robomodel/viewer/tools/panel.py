"""The Tools folders (rqt in the page) and the graph watch that feeds their topic choices."""

from __future__ import annotations

import threading

from robomodel.viewer.tools.base import ToolContext
from robomodel.viewer.tools.params import ParameterTool
from robomodel.viewer.tools.plot import PlotTool
from robomodel.viewer.tools.publisher import PublisherTool
from robomodel.viewer.tools.simulation import SimulationTool
from robomodel.viewer.tools.steering import SteeringTool

__all__ = ["ToolsPanel"]

_GRAPH_PERIOD_S = 1.0


class ToolsPanel:
    """Builds one collapsed folder per tool and keeps the graph (topics, nodes) current."""

    def __init__(self, tools: ToolContext) -> None:
        self.tools = tools
        gui = tools.server.gui
        with gui.add_folder("Simulation", expand_by_default=False):
            self.simulation = SimulationTool(tools)
        with gui.add_folder("Robot Steering", expand_by_default=False):
            self.steering = SteeringTool(tools)
        with gui.add_folder("Plot", expand_by_default=False):
            self.plot = PlotTool(tools)
        with gui.add_folder("Topic Publisher", expand_by_default=False):
            self.publisher = PublisherTool(tools)
        with gui.add_folder("Parameters", expand_by_default=False) as folder:
            self.parameters = ParameterTool(tools, folder)
        self.graph_updates = 0
        self._stop = threading.Event()
        self._pending = threading.Event()
        self._thread = threading.Thread(
            target=self._watch, name="robomodel-view-graph", daemon=True
        )
        self._thread.start()

    def _watch(self) -> None:
        while not self._stop.is_set():
            if not self._pending.is_set():
                self._pending.set()
                self.tools.bus.submit(self.refresh_graph)
            self._stop.wait(_GRAPH_PERIOD_S)

    def refresh_graph(self) -> None:
        """Ask the bus for its topics and nodes (bus worker thread)."""
        try:
            context = self.tools.node.context
            graph = self.tools.bus.query(lambda: context.graph(timeout_s=0.5))
            self.tools.topics = {name: set(info.types) for name, info in graph.topics.items()}
            self.tools.nodes = set(graph.nodes)
            self.tools.services = set(graph.services)
            self.tools.learn_unknown_types()
            self.parameters.update_nodes(self.tools.nodes)
            self.steering.follow_graph(self.tools.topics)
            self.graph_updates += 1
        finally:
            self._pending.clear()

    def close(self) -> None:
        self._stop.set()
        self._thread.join(timeout=5)
        self.tools.bus.close()
