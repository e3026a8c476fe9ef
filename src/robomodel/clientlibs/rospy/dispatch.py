"""Where rospy's topic callbacks run, as rospy runs them: on threads of the topic, not on one
thread of the node. rospy calls a topic's callbacks on the thread that reads its connection, so
a slow callback on one topic does not delay another topic's; here each subscribed topic has a
thread of its own, which calls the callbacks of every Subscriber of the topic in this process
(rospy's ``_SubscriberImpl``: one per topic, shared by its Subscribers) for one message after
the other, in the order the messages came. ``queue_size`` messages wait, the oldest dropped
first (rospy drops the oldest too; ``None`` keeps them all).

Bound: at most ``MAX_TOPIC_THREADS`` topic threads in a process. Past it a new topic shares the
thread that serves the fewest topics (with one warning), and the topics sharing a thread take
turns, one message each. :func:`topic_threads` counts them; a thread ends with its last topic.
"""

from __future__ import annotations

import collections
import queue
import threading
import traceback
from collections.abc import Callable
from typing import Any

from robomodel.clientlibs.rospy import core

__all__ = ["MAX_TOPIC_THREADS", "TopicDispatch", "close_all", "topic_threads"]

_OPEN: set[TopicDispatch] = set()

# rospy has one thread per publisher connection, without bound; a node subscribes to a handful
# of topics. 64 threads cost a few MiB and leave room for a monitor node's many topics.
MAX_TOPIC_THREADS = 64
UNBOUNDED = 100_000  # rospy's queue_size=None keeps every message; robomodel's queue is bounded

Callback = tuple[Callable[..., Any], Any]  # (callback, callback_args or None)


class _Worker:
    """A thread that runs the callbacks of the topics it serves, taking turns between them.

    ``ready`` holds each topic with waiting messages once, in turn (``None`` ends the thread):
    a ``queue.SimpleQueue``, whose hand-off between threads is CPython's cheapest (about 23 us
    against 29 us for a ``threading.Condition`` here, of a message's ~240 us between processes)."""

    def __init__(self, name: str) -> None:
        self.lock = threading.Lock()
        self.ready: queue.SimpleQueue[TopicDispatch | None] = queue.SimpleQueue()
        self.topics = 0
        self.thread = threading.Thread(target=self._run, name=f"rospy {name}", daemon=True)
        self.thread.start()

    def _run(self) -> None:
        while (topic := self.ready.get()) is not None:
            with self.lock:
                if not topic.queue:  # closed while it waited for its turn
                    topic.scheduled = False
                    continue
                msg = topic.queue.popleft()
                if topic.queue:
                    self.ready.put(topic)  # its next message after the other topics' turns
                else:
                    topic.scheduled = False
            topic.invoke(msg)


class _Pool:
    def __init__(self) -> None:
        self.lock = threading.Lock()
        self.workers: list[_Worker] = []
        self.warned = False

    def take(self, name: str) -> _Worker:
        with self.lock:
            if len(self.workers) < MAX_TOPIC_THREADS:
                worker = _Worker(name)
                self.workers.append(worker)
            else:
                worker = min(self.workers, key=lambda w: w.topics)
                if not self.warned:
                    self.warned = True
                    core.logwarn(
                        f"more than {MAX_TOPIC_THREADS} subscribed topics (MAX_TOPIC_THREADS):"
                        f" {name} shares a callback thread with other topics"
                    )
            worker.topics += 1
            return worker

    def give(self, worker: _Worker) -> None:
        with self.lock:
            worker.topics -= 1
            if worker.topics > 0:
                return
            self.workers.remove(worker)
        worker.ready.put(None)


_POOL = _Pool()


def topic_threads() -> int:
    """The topic callback threads of this process now."""
    with _POOL.lock:
        return len(_POOL.workers)


class TopicDispatch:
    """One subscribed topic's waiting messages and callbacks, served by one thread."""

    def __init__(self, topic: str, depth: int | None) -> None:
        self.topic = topic
        self.callbacks: list[Callback] = []
        self.queue: collections.deque[Any] = collections.deque(maxlen=depth or UNBOUNDED)
        self.scheduled = False
        self.dropped = 0
        self._worker: _Worker | None = _POOL.take(topic)
        _OPEN.add(self)

    def set_depth(self, depth: int) -> None:
        """A new ``queue_size`` (rospy: the last Subscriber's that gave one)."""
        worker = self._worker
        if worker is None:
            return
        with worker.lock:
            self.queue = collections.deque(self.queue, maxlen=depth)

    def put(self, msg: Any) -> None:
        """Queue ``msg`` for the callbacks (any thread: a connection's reader)."""
        worker = self._worker
        if worker is None:
            return
        with worker.lock:
            if len(self.queue) == self.queue.maxlen:
                self.dropped += 1
            self.queue.append(msg)
            if not self.scheduled:
                self.scheduled = True
                worker.ready.put(self)

    def invoke(self, msg: Any) -> None:
        """Call every callback with ``msg``; as rospy, a callback's exception is logged and the
        next callback still runs; after shutdown no callback runs."""
        for callback, args in list(self.callbacks):
            if core.is_shutdown():
                return
            try:
                if args is None:
                    callback(msg)
                else:
                    callback(msg, args)
            except Exception:
                core.logerr(f"bad callback: {callback}\n{traceback.format_exc()}")

    def close(self) -> None:
        """Stop: waiting messages are dropped, and the thread ends with its last topic."""
        worker, self._worker = self._worker, None
        if worker is None:
            return
        with worker.lock:
            self.queue.clear()  # its turn, if it has one waiting, finds nothing
            self.scheduled = False
        _POOL.give(worker)
        _OPEN.discard(self)


def close_all() -> None:
    """Stop every topic's thread (the node shut down)."""
    for dispatch in list(_OPEN):
        dispatch.close()


core.after_teardown(close_all)
