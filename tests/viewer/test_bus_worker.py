"""The viewer's bus worker: a query that fails goes on to the next one."""

from __future__ import annotations

import logging
import threading

import pytest

from robomodel.errors import RobomodelError
from robomodel.runtime.context import Context
from robomodel.viewer.tools.base import BusWorker
from tests.timing import scaled


def test_a_query_the_bus_did_not_answer_is_one_line_and_the_next_runs(
    caplog: pytest.LogCaptureFixture,
) -> None:
    context = Context(bus="inproc")
    worker = BusWorker(context)
    ran = threading.Event()

    def unanswered() -> None:
        raise RobomodelError("the viewer's loop did not answer")

    try:
        with caplog.at_level(logging.WARNING, logger="robomodel.viewer"):
            worker.submit(unanswered)
            worker.submit(ran.set)
            assert ran.wait(scaled(5))
        [record] = [r for r in caplog.records if r.name == "robomodel.viewer"]
        assert record.getMessage() == (
            "robomodel view: a bus query failed: the viewer's loop did not answer"
        )
        assert record.exc_info is None  # no traceback for a bus that did not answer
    finally:
        worker.close()
        context.shutdown()
