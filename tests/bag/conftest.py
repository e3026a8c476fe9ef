"""Processes for the bag tests: a publisher of a known /joint_states sequence, the CLI."""

from __future__ import annotations

import json
import signal
import subprocess
import sys
import textwrap
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from tests.conftest import ROBOMODEL, end_process, unique_domain
from tests.timing import scaled

TALKER = textwrap.dedent(
    """
    import sys
    from robomodel.runtime import Context, latched
    from robomodel.runtime.msg import Header, JointState, String, Time
    ctx = Context("zenoh", domain_id=int(sys.argv[1]))
    limit = int(sys.argv[2])
    period_s = float(sys.argv[3])
    node = ctx.create_node("talker")
    pub = node.create_publisher(JointState, "/joint_states")
    node.create_publisher(String, "/robot_description", latched()).publish(String("<robot/>"))
    count = [0]
    def tick():
        if limit and count[0] >= limit:
            return
        count[0] += 1
        k = count[0]
        pub.publish(JointState(
            header=Header(Time(k, 1000 * k), "base"),
            name=["a", "b"], position=[0.1 * k, -0.5 * k], velocity=[float(k)], effort=[],
        ))
    node.create_timer(period_s, tick)
    print("ready", flush=True)
    try:
        ctx.spin()
    except KeyboardInterrupt:
        pass
    ctx.shutdown()
    """
)


def flushed_count(folder: Path) -> int:
    """The message count metadata.yaml says is flushed so far (0 before the first flush)."""
    import yaml

    try:
        meta = yaml.safe_load((folder / "metadata.yaml").read_text())
    except (OSError, yaml.YAMLError):
        return 0
    return int(meta["rosbag2_bagfile_information"]["message_count"])


def flushed_counts(folder: Path) -> dict[str, int]:
    """Each topic's message count metadata.yaml says is flushed so far (none before the first
    flush)."""
    import yaml

    try:
        meta = yaml.safe_load((folder / "metadata.yaml").read_text())
    except (OSError, yaml.YAMLError):
        return {}
    return {
        entry["topic_metadata"]["name"]: int(entry["message_count"])
        for entry in meta["rosbag2_bagfile_information"]["topics_with_message_count"]
    }


def run_cli(*args: str, timeout: float | None = None) -> subprocess.CompletedProcess[str]:
    timeout = scaled(30) if timeout is None else timeout
    return subprocess.run([*ROBOMODEL, *args], capture_output=True, text=True, timeout=timeout)


def stop(proc: subprocess.Popen[str], sig: int = signal.SIGTERM) -> None:
    end_process(proc, sig)


class Talker:
    def __init__(self, tmp_path: Path, *, limit: int = 0, period_s: float = 0.01) -> None:
        script = tmp_path / "talker.py"
        script.write_text(TALKER)
        self.domain = unique_domain()
        self.proc = subprocess.Popen(
            [sys.executable, str(script), self.domain, str(limit), str(period_s)],
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
        )
        assert self.proc.stdout is not None and self.proc.stdout.readline().strip() == "ready"


@pytest.fixture
def talker(tmp_path: Path) -> Iterator[Talker]:
    started = Talker(tmp_path)
    yield started
    stop(started.proc)


ROSBAGS_READ = textwrap.dedent(
    """
    import hashlib, json, sys
    from rosbags.rosbag2 import Reader
    from rosbags.typesys import get_typestore, Stores, get_types_from_msg
    bags = []
    for folder in sys.argv[1:]:
        store = get_typestore(Stores.EMPTY)
        out = {"messages": [], "positions": [], "topics": {}}
        with Reader(folder) as reader:
            out["count"] = reader.message_count
            for conn in reader.connections:
                store.register(get_types_from_msg(conn.msgdef.data, conn.msgtype))
                durability = [q.durability.name for q in conn.ext.offered_qos_profiles]
                out["topics"][conn.topic] = [conn.msgtype, durability]
            for conn, stamp, data in reader.messages():
                out["messages"].append([conn.topic, stamp, hashlib.sha256(data).hexdigest()])
                if conn.topic == "/joint_states":
                    msg = store.deserialize_cdr(data, conn.msgtype)
                    out["positions"].append(msg.position.tolist())
        bags.append(out)
    print(json.dumps(bags))
    """
)


def rosbags_read(tmp_path: Path, *folders: Path) -> list[dict[str, Any]]:
    """What rosbags' rosbag2 reader, in a process of its own, reads from each folder."""
    script = tmp_path / "rosbags_read.py"
    script.write_text(ROSBAGS_READ)
    done = subprocess.run(
        [sys.executable, str(script), *map(str, folders)],
        capture_output=True, text=True, timeout=scaled(60),
    )  # fmt: skip
    assert done.returncode == 0, done.stderr
    result: list[dict[str, Any]] = json.loads(done.stdout)
    return result
