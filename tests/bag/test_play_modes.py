"""``bag play --loop``, ``--clock`` and latching, seen by a subscriber in another process.

The bag is written with :class:`McapFolderWriter` with known times, so what the subscriber must
see is known exactly: the /joint_states sequence (again with ``--loop``), /clock values inside
the bag's span that follow the bag's time (not the wall clock), and the latched topics
(/robot_description, /tf_static and a topic offered transient local) delivered to a subscriber
that joins after they were published, while a volatile topic is not.
"""

from __future__ import annotations

import signal
import subprocess
import time
from collections.abc import Callable
from pathlib import Path

from robomodel.bag import McapFolderWriter
from robomodel.runtime import Context
from robomodel.runtime.msg import (
    Clock,
    Header,
    JointState,
    Message,
    String,
    TFMessage,
    Time,
    TransformStamped,
    serialize,
)
from robomodel.runtime.qos import QoSProfile, latched
from tests.conftest import ROBOMODEL, unique_domain
from tests.timing import scaled

from .conftest import stop

T0 = 1_700_000_000_000_000_000
STEP_NS = 50_000_000  # /joint_states every 50 ms of bag time


def _write_bag(folder: Path, states: int) -> tuple[int, int]:
    """Latched topics at T0, a volatile /chatter, then ``states`` /joint_states; the span."""
    writer = McapFolderWriter(folder)
    volatile = (QoSProfile(10),)
    writer.add_topic("/robot_description", String, (latched(),))
    writer.add_topic("/tf_static", TFMessage, volatile)  # latched on replay whatever offered
    writer.add_topic("/status", String, (latched(),))  # recorded as latched
    writer.add_topic("/chatter", String, volatile)
    writer.add_topic("/joint_states", JointState, volatile)
    first: list[tuple[str, Message]] = [
        ("/robot_description", String("<robot/>")),
        *(
            ("/tf_static", TFMessage([TransformStamped(Header(Time(1, 0), "base"), child)]))
            for child in ("a", "b")
        ),
        ("/status", String("ok")),
        ("/chatter", String("hi")),
    ]
    for k, (topic, msg) in enumerate(first):
        writer.write(topic, serialize(msg), T0 + k, T0 + k)
    end = T0
    for k in range(states):
        end = T0 + STEP_NS * (k + 1)
        state = JointState(Header(Time(k, 0), "base"), ["j"], [float(k)])
        writer.write("/joint_states", serialize(state), end, end)
    writer.close()
    return T0, end


class _Probe:
    """A Zenoh subscriber process of its own (the test's), collecting what it receives."""

    def __init__(self, context: Context) -> None:
        self.context = context
        self.node = context.create_node("probe")
        self.seen: dict[str, list[tuple[float, Message]]] = {}

    def listen(self, topic: str, cls: type[Message], qos: QoSProfile | int = 100) -> None:
        got = self.seen.setdefault(topic, [])
        self.node.create_subscription(cls, topic, lambda m: got.append((time.monotonic(), m)), qos)

    def wait(self, done: Callable[[], bool], timeout_s: float = 30) -> None:
        deadline = time.monotonic() + scaled(timeout_s)
        self.context.spin(until=lambda: done() or time.monotonic() > deadline)
        counts = {t: len(v) for t, v in self.seen.items()}
        assert done(), f"timed out; seen {counts}"

    def positions(self) -> list[float]:
        return [m.position[0] for _, m in self.seen.get("/joint_states", [])]  # type: ignore[attr-defined]


def _play(folder: Path, domain: str, *options: str) -> subprocess.Popen[str]:
    return subprocess.Popen(
        [*ROBOMODEL, "bag", "play", str(folder), *options, "--domain-id", domain],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
    )  # fmt: skip


def test_loop_replays_the_bag_again_and_again(tmp_path: Path) -> None:
    states = 10
    _write_bag(tmp_path / "b", states)
    domain = unique_domain()
    with Context("zenoh", domain_id=int(domain)) as context:
        probe = _Probe(context)
        probe.listen("/joint_states", JointState)
        play = _play(tmp_path / "b", domain, "--loop", "--rate", "2")
        try:
            probe.wait(lambda: len(probe.positions()) >= 3 * states)
            assert play.poll() is None  # still playing after three passes
        finally:
            stop(play, signal.SIGINT)
        _, err = play.communicate()
    assert play.returncode == 0, err
    seen = probe.positions()
    start = seen.index(0.0)  # the first pass from its start (a subscriber may match late)
    assert seen[start : start + 2 * states] == [float(k) for k in range(states)] * 2
    played = int(err.split("played ")[1].split()[0])
    assert played >= 3 * (states + 5)  # every topic, each pass


def test_clock_follows_the_bag_time(tmp_path: Path) -> None:
    start_ns, end_ns = _write_bag(tmp_path / "b", 30)  # 1.5 s of bag time
    domain = unique_domain()
    with Context("zenoh", domain_id=int(domain)) as context:
        probe = _Probe(context)
        probe.listen("/clock", Clock)
        probe.listen("/joint_states", JointState)
        play = _play(tmp_path / "b", domain, "--clock", "50", "--rate", "2")
        try:
            probe.wait(lambda: play.poll() is not None and len(probe.positions()) >= 30)
        finally:
            stop(play)
    assert play.returncode == 0, play.stderr.read() if play.stderr else ""
    ticks = [(at, m.clock.sec * 1_000_000_000 + m.clock.nanosec) for at, m in probe.seen["/clock"]]  # type: ignore[attr-defined]
    stamps = [s for _, s in ticks]
    assert all(start_ns <= s <= end_ns for s in stamps)  # inside the bag's span
    assert stamps == sorted(stamps) and len(set(stamps)) > 0.8 * len(stamps)  # increasing
    assert stamps[-1] - stamps[0] > 0.8 * (end_ns - start_ns)  # through the whole bag
    # 50 Hz of wall time over 0.75 s (1.5 s of bag at rate 2): about 37 ticks, not one per message
    assert 15 <= len(ticks) <= 60
    wall = ticks[-1][0] - ticks[0][0]
    assert 1.4 < (stamps[-1] - stamps[0]) / 1e9 / wall < 2.6  # bag time runs at --rate


def test_latched_topics_reach_a_subscriber_that_joins_late(tmp_path: Path) -> None:
    _write_bag(tmp_path / "b", 60)  # 3 s of /joint_states after the latched topics
    domain = unique_domain()
    late = {"/robot_description": String, "/tf_static": TFMessage, "/status": String}
    with Context("zenoh", domain_id=int(domain)) as context:
        probe = _Probe(context)
        probe.listen("/joint_states", JointState)
        play = _play(tmp_path / "b", domain)
        try:
            probe.wait(lambda: len(probe.positions()) >= 6)  # 0.3 s after the latched ones
            assert play.poll() is None
            for topic, cls in {**late, "/chatter": String}.items():
                probe.listen(topic, cls, latched(10))
            # the player is the only publisher: what arrives came from it while it played (on
            # a loaded machine the late subscription's discovery can outlast the bag's 3 s)
            probe.wait(lambda: all(probe.seen[t] for t in late))
            probe.wait(lambda: play.poll() is not None)
        finally:
            stop(play)
    assert play.returncode == 0
    data = {t: [m for _, m in probe.seen[t]] for t in (*late, "/chatter")}
    assert [m.data for m in data["/robot_description"]] == ["<robot/>"]  # type: ignore[attr-defined]
    assert [m.data for m in data["/status"]] == ["ok"]  # type: ignore[attr-defined]
    children = [t.child_frame_id for m in data["/tf_static"] for t in m.transforms]  # type: ignore[attr-defined]
    assert children == ["a", "b"]  # every static transform, not only the last message
    assert data["/chatter"] == []  # volatile: not latched on replay
