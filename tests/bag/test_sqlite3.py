"""``bag record --storage sqlite3`` read back by rosbags (a process of its own) with the same
contents as an MCAP recording of the same messages; the progress line of ``bag record``."""

from __future__ import annotations

import re
import subprocess
import sys
import textwrap
from pathlib import Path

from robomodel.bag import RecorderStats
from robomodel.cli.bag import format_progress
from tests.conftest import ROBOMODEL, unique_domain
from tests.timing import scaled

from .conftest import rosbags_read, stop

COUNT = 60

# Publishes COUNT /joint_states once two recorders subscribe, so both get every message.
GATED_TALKER = textwrap.dedent(
    """
    import sys, time
    from robomodel.runtime import Context, latched
    from robomodel.runtime.msg import Header, JointState, String, Time
    ctx = Context("zenoh", domain_id=int(sys.argv[1]))
    node = ctx.create_node("talker")
    pub = node.create_publisher(JointState, "/joint_states")
    node.create_publisher(String, "/robot_description", latched()).publish(String("<robot/>"))
    def recorders():
        info = ctx.graph(timeout_s=0.3).topics.get("/joint_states")
        return len(info.subscribers) if info else 0
    deadline = time.monotonic() + float(sys.argv[3])  # scaled by the test
    while recorders() < 2 and time.monotonic() < deadline:
        ctx.spin(duration_s=0.1)
    ctx.spin(duration_s=0.5)
    for k in range(1, int(sys.argv[2]) + 1):
        pub.publish(JointState(header=Header(Time(k, 0), "base"), name=["a", "b"],
                               position=[0.1 * k, -0.5 * k], velocity=[float(k)]))
        ctx.spin(duration_s=0.01)
    ctx.spin(duration_s=0.5)
    print("done", flush=True)
    try:
        ctx.spin()
    except KeyboardInterrupt:
        pass
    ctx.shutdown()
    """
)

_ANSI = re.compile(r"\x1b\[[0-9;?]*[A-Za-z]")
_PROGRESS = re.compile(
    r"Recording: (\d+) messages, ([\d.]+ (?:B|KiB|MiB)), ([\d.]+) s, (\d+) topics"
)


def _record(
    folder: Path, domain: str, *options: str, env: dict[str, str] | None = None
) -> subprocess.Popen[str]:
    return subprocess.Popen(
        [*ROBOMODEL, "bag", "record", "/joint_states", "/robot_description", "-o", str(folder),
         *options, "--domain-id", domain],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env,
    )  # fmt: skip


def test_sqlite3_recording_reads_as_the_mcap_one(tmp_path: Path) -> None:
    import os

    domain = unique_domain()
    script = tmp_path / "talker.py"
    script.write_text(GATED_TALKER)
    talker = subprocess.Popen(
        [sys.executable, str(script), domain, str(COUNT), str(scaled(30))],
        stdout=subprocess.PIPE,
        text=True,
    )
    mcap, sqlite = tmp_path / "mcap", tmp_path / "sqlite"
    forced = {**os.environ, "TTY_COMPATIBLE": "1"}  # rich's switch: draw as on a terminal
    recorders = [
        _record(mcap, domain),
        _record(sqlite, domain, "--storage", "sqlite3", env=forced),
    ]
    try:
        assert talker.stdout is not None and talker.stdout.readline().strip() == "done"
        for proc in recorders:
            stop(proc)
        results = [(r.returncode, r.communicate()[1]) for r in recorders]
    finally:
        for proc in (*recorders, talker):
            stop(proc)
    for code, err in results:
        assert code == 0, err
    assert (sqlite / "metadata.yaml").exists() and list(sqlite.glob("*.db3"))
    assert not list(sqlite.glob("*.mcap"))

    theirs_mcap, theirs_sqlite = rosbags_read(tmp_path, mcap, sqlite)
    assert theirs_sqlite["count"] == theirs_mcap["count"] == COUNT + 1
    for kind in (theirs_mcap, theirs_sqlite):
        assert kind["positions"] == [[0.1 * k, -0.5 * k] for k in range(1, COUNT + 1)]
    same = [[[t, h] for t, _, h in bag["messages"]] for bag in (theirs_mcap, theirs_sqlite)]
    assert sorted(same[0]) == sorted(same[1])  # the same bytes on the same topics
    states = [[t, h] for t, h in same[0] if t == "/joint_states"]
    assert states == [[t, h] for t, h in same[1] if t == "/joint_states"]  # in the same order
    assert (
        theirs_sqlite["topics"]
        == theirs_mcap["topics"]
        == {
            "/joint_states": ["sensor_msgs/msg/JointState", ["VOLATILE"]],
            "/robot_description": ["std_msgs/msg/String", ["TRANSIENT_LOCAL"]],
        }
    )  # types and offered QoS (latched or not) kept by both storages

    # the progress line, drawn when stderr is a terminal (forced) and not otherwise
    assert "Recording:" not in results[0][1]
    lines = _PROGRESS.findall(_ANSI.sub("", results[1][1]))
    assert len(lines) >= 2, results[1][1]
    counts = [int(messages) for messages, *_ in lines]
    assert counts == sorted(counts) and counts[-1] == COUNT + 1
    assert [float(seconds) for _, _, seconds, _ in lines] == sorted(
        float(s) for _, _, s, _ in lines
    )
    assert lines[-1][3] == "2" and lines[-1][1].endswith("KiB")


def test_progress_line_format() -> None:
    stats = RecorderStats(
        messages=1234, size_bytes=3 * 1024 * 1024 + 512 * 1024, duration_s=12.34, topics=5
    )
    assert format_progress(stats) == "Recording: 1234 messages, 3.5 MiB, 12.3 s, 5 topics"
    assert (
        format_progress(RecorderStats(0, 512, 0.04, 0))
        == "Recording: 0 messages, 512 B, 0.0 s, 0 topics"
    )
