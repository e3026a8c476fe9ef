"""``topic list`` waits for discovery instead of printing a partial graph."""

from __future__ import annotations

from types import SimpleNamespace
from typing import Any

from robomodel.cli._bus import settled_graph
from robomodel.runtime.transport.base import Endpoint, Graph
from tests.timing import scaled


def _graph(*topics: str) -> Graph:
    graph = Graph()
    for topic in topics:
        graph.add("pub", Endpoint(node="/sim", topic=topic, type_name="std_msgs/msg/String"))
    return graph


class _Discovering:
    """A context whose graph fills in over a few queries, as liveliness tokens arrive."""

    def __init__(self, answers: list[Graph]) -> None:
        self.transport = SimpleNamespace(name="inproc")
        self.answers = answers
        self.queries = 0

    def graph(self, timeout_s: float = 1.0) -> Graph:
        answer = self.answers[min(self.queries, len(self.answers) - 1)]
        self.queries += 1
        return answer


def test_empty_and_partial_answers_are_not_printed() -> None:
    full = _graph("/clock", "/tf", "/odom")
    context = _Discovering([Graph(), _graph("/clock"), full, full])
    result = settled_graph(context, timeout_s=scaled(5.0))  # type: ignore[arg-type]
    assert sorted(result.topics) == ["/clock", "/odom", "/tf"]
    assert context.queries == 4


def test_an_empty_domain_answers_within_the_timeout() -> None:
    context = _Discovering([Graph()])
    result: Any = settled_graph(context, timeout_s=scaled(0.3))  # type: ignore[arg-type]
    assert result.topics == {}
