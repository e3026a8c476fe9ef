"""What every tool gets from the viewer, and the worker that asks the bus without blocking it.

Tools follow the viewer's threading rule: nodes, publishers, subscriptions and timers are only
touched on the viewer's loop thread (``post``). Graph and parameter queries can wait on other
processes (Zenoh) or on the loop thread itself (a node of this process answers on it), so they
run on a worker thread of their own.
"""

from __future__ import annotations

import logging
import queue
import threading
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from robomodel.errors import RobomodelError
from robomodel.runtime.context import Context
from robomodel.runtime.msg import Message, MessageTypeError, get_message_type
from robomodel.runtime.node import Node

__all__ = ["BusWorker", "ToolContext"]


log = logging.getLogger("robomodel.viewer")


class BusWorker:
    """Runs bus queries one at a time on a thread of its own.

    On the in-process bus a parameter call runs the node's handler in the caller's thread, so
    there the query is handed to the loop thread and the worker waits for it.
    """

    def __init__(self, context: Context) -> None:
        self.context = context
        self._jobs: queue.SimpleQueue[Callable[[], object] | None] = queue.SimpleQueue()
        self._thread = threading.Thread(target=self._run, name="robomodel-view-bus", daemon=True)
        self._thread.start()

    def _run(self) -> None:
        while (job := self._jobs.get()) is not None:
            try:
                job()
            except RobomodelError as exc:  # the bus or the loop did not answer: one line
                log.warning("robomodel view: a bus query failed: %s", exc)
            except Exception:  # a failed query must not end the worker
                log.exception("bus query failed")

    def submit(self, job: Callable[[], object]) -> None:
        self._jobs.put(job)

    def query(self, call: Callable[[], Any], timeout_s: float = 5.0) -> Any:
        """``call()`` on the loop thread (in-process bus) or here (Zenoh); worker thread only."""
        if self.context.transport.name != "inproc":
            return call()
        done = threading.Event()
        box: dict[str, Any] = {}

        def run() -> None:
            try:
                box["value"] = call()
            except Exception as exc:
                box["error"] = exc
            done.set()

        self.context.executor.post(run)
        if not done.wait(timeout_s):
            raise RobomodelError("the viewer's loop did not answer")
        if "error" in box:
            raise box["error"]
        return box["value"]

    def close(self) -> None:
        self._jobs.put(None)
        self._thread.join(timeout=5)


@dataclass
class ToolContext:
    """The viewer's parts a tool uses.

    Attributes:
        server: The viser server (``.gui`` and ``.scene``).
        node: The viewer's node (publishers and subscriptions of the tools).
        post: Runs a callable on the loop thread.
        bus: The query worker.
        buffer: The viewer's TF buffer.
        fixed_frame: Returns the current fixed frame.
        topics: Topic name to type names, as last seen in the graph (updated by the viewer).
        nodes: Node names, as last seen in the graph.
        services: Service names, as last seen in the graph.
    """

    server: Any
    node: Node
    post: Callable[[Callable[[], object]], None]
    bus: BusWorker
    buffer: Any
    fixed_frame: Callable[[], str]
    topics: dict[str, set[str]] = field(default_factory=dict)
    nodes: set[str] = field(default_factory=set)
    services: set[str] = field(default_factory=set)
    _asked: set[tuple[str, ...]] = field(default_factory=set)

    def topic_types(self) -> dict[str, type[Message]]:
        """Topics with one known message type, as classes."""
        out: dict[str, type[Message]] = {}
        for name, types in list(self.topics.items()):
            if len(types) == 1:
                try:
                    out[name] = get_message_type(next(iter(types)))
                except MessageTypeError:
                    continue
        return out

    def learn_unknown_types(self) -> None:
        """On the ROS 1 bus, learn the types of topics no package or store has from their
        publishers' definitions (as ``topic echo`` does), so the plot takes them too; each
        topic is asked once (bus worker thread: a probe may take seconds)."""
        from robomodel.runtime.transport.ros1.definition_probe import learn_topic_type

        for name, types in list(self.topics.items()):
            if len(types) != 1 or (name, *types) in self._asked:
                continue
            try:
                get_message_type(next(iter(types)))
            except MessageTypeError:
                self._asked.add((name, *types))
                try:
                    learn_topic_type(self.node.context.transport, name)
                except MessageTypeError as exc:  # a definition robomodel refuses: this topic only
                    log.warning("not showing %s: %s", name, exc)

    def topics_of_type(self, type_name: str) -> list[str]:
        return sorted(n for n, types in list(self.topics.items()) if type_name in types)
