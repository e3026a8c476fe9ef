"""``robomodel bag record``: a simulation run read back by the mcap library and by rosbags (in
a process of its own) with identical contents; ``--ros1`` read by Debian's ``rosbag info``;
a recording killed with SIGKILL still read."""

from __future__ import annotations

import json
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

from robomodel.runtime.msg import JointState, deserialize
from tests.conftest import EXAMPLES, ROBOMODEL, past_the_bus_line, unique_domain
from tests.timing import scaled

from .conftest import Talker, flushed_count, run_cli, stop

RRBOT = EXAMPLES / "rrbot_description/urdf/rrbot.xacro"
RRBOT_YAML = EXAMPLES / "rrbot_description/config/rrbot_control.yaml"

ROSBAGS_DUMP = textwrap.dedent(
    """
    import hashlib, json, sys
    from rosbags.rosbag2 import Reader
    from rosbags.typesys import get_typestore, Stores, get_types_from_msg
    store = get_typestore(Stores.EMPTY)
    out = {"messages": [], "joint_states": []}
    with Reader(sys.argv[1]) as reader:
        for conn in reader.connections:
            store.register(get_types_from_msg(conn.msgdef.data, conn.msgtype))
        for conn, stamp, data in reader.messages():
            out["messages"].append([conn.topic, stamp, hashlib.sha256(data).hexdigest()])
            if conn.topic == "/joint_states":
                msg = store.deserialize_cdr(data, conn.msgtype)
                out["joint_states"].append([list(msg.name), msg.position.tolist()])
    print(json.dumps(out))
    """
)


def _mcap_messages(folder: Path) -> list[tuple[str, int, int, bytes, str]]:
    from mcap.reader import make_reader

    out = []
    for path in sorted(folder.glob("*.mcap")):
        with path.open("rb") as handle:
            reader = make_reader(handle)
            assert reader.get_header().profile == "ros2"
            for schema, channel, message in reader.iter_messages(log_time_order=False):
                assert channel.message_encoding == "cdr" and schema.encoding == "ros2msg"
                out.append(
                    (
                        channel.topic,
                        message.log_time,
                        message.publish_time,
                        message.data,
                        schema.name,
                    )
                )
    return out


def test_simulation_run_read_back_by_mcap_and_rosbags(tmp_path: Path) -> None:
    import hashlib

    domain = unique_domain()
    started_ns = time.time_ns()
    sim = subprocess.Popen(
        [*ROBOMODEL, "sim", str(RRBOT), "--controllers", str(RRBOT_YAML), "--headless",
         "--rate", "1", "--domain-id", domain],
        stderr=subprocess.PIPE, text=True,
    )  # fmt: skip
    out = tmp_path / "run"
    try:
        assert sim.stderr is not None and "robomodel sim: world" in past_the_bus_line(sim.stderr)
        rec = run_cli(
            "bag", "record", "-a", "-o", str(out), "--duration", f"{scaled(3):.1f}",
            "--domain-id", domain,
        )  # fmt: skip
        recorded_ns = time.time_ns()
    finally:
        stop(sim)
    assert rec.returncode == 0, rec.stderr
    ours = _mcap_messages(out)
    topics = {m[0] for m in ours}
    assert {"/joint_states", "/clock", "/tf", "/tf_static", "/robot_description"} <= topics
    # publish time is the simulator's send time (wall clock, not sim time), log time our
    # receive time: both within the run, in that order. No bound between the two: a latched
    # message (/robot_description) is received whenever the recorder joins, and a loaded
    # machine delays the others too.
    assert all(started_ns <= pub <= log <= recorded_ns for _, log, pub, _, _ in ours)
    assert any(log != pub for _, log, pub, _, _ in ours)
    script = tmp_path / "dump.py"
    script.write_text(ROSBAGS_DUMP)
    dumped = subprocess.run(
        [sys.executable, str(script), str(out)], capture_output=True, text=True, timeout=scaled(60)
    )
    assert dumped.returncode == 0, dumped.stderr
    theirs = json.loads(dumped.stdout)
    mine = sorted((t, log, hashlib.sha256(d).hexdigest()) for t, log, _, d, _ in ours)
    assert sorted(tuple(m) for m in theirs["messages"]) == mine
    states = [deserialize(d, JointState) for t, _, _, d, _ in ours if t == "/joint_states"]
    assert len(states) > 10
    assert theirs["joint_states"] == [[list(s.name), list(s.position)] for s in states]


def _rosbag_info(path: Path) -> dict[str, object]:
    import yaml

    done = subprocess.run(
        ["rosbag", "info", "--yaml", str(path)], capture_output=True, text=True, timeout=scaled(60)
    )
    assert done.returncode == 0, done.stderr
    info = yaml.safe_load(done.stdout)
    assert isinstance(info, dict)
    return info


def test_ros1_recording_accepted_by_debian_rosbag(tmp_path: Path) -> None:
    talker = Talker(tmp_path, period_s=0.02)
    out = tmp_path / "run.bag"
    try:  # longer on a busy machine, where the talker and the recorder start late
        rec = run_cli(
            "bag", "record", "/joint_states", "/robot_description", "--ros1", str(out),
            "--duration", f"{scaled(2.5):.1f}", "--domain-id", talker.domain,
        )  # fmt: skip
    finally:
        stop(talker.proc)
    assert rec.returncode == 0, rec.stderr
    assert not out.with_name("run.bag.active").exists()
    recorded = int(rec.stderr.split("recorded ")[1].split()[0])
    info = _rosbag_info(out)
    assert info["messages"] == recorded
    topics = {t["topic"]: (t["type"], t["messages"]) for t in info["topics"]}  # type: ignore[attr-defined]
    count = topics["/joint_states"][1]
    assert topics["/joint_states"][0] == "sensor_msgs/JointState" and count > 50  # 50 Hz, ~1.5 s
    assert topics["/robot_description"] == ("std_msgs/String", 1)  # latched: recorded anyway
    assert count + 1 == recorded
    ours = run_cli("bag", "info", str(out))
    assert ours.returncode == 0, ours.stderr
    assert (
        f"Topic: /joint_states | Type: sensor_msgs/msg/JointState | Count: {count} " in ours.stdout
    )


def test_sigkilled_recording_is_read(tmp_path: Path) -> None:
    talker = Talker(tmp_path, period_s=0.005)
    out = tmp_path / "killed"
    rec = subprocess.Popen(
        [*ROBOMODEL, "bag", "record", "/joint_states", "-o", str(out), "--domain-id",
         talker.domain], stderr=subprocess.PIPE, text=True,
    )  # fmt: skip
    try:
        deadline = time.monotonic() + scaled(20)
        while flushed_count(out) < 50 and time.monotonic() < deadline:
            time.sleep(0.05)  # until a flush with messages (metadata.yaml follows each flush)
        flushed = flushed_count(out)
        time.sleep(0.5)  # killed between two flushes
    finally:
        stop(rec, signal.SIGKILL)
        stop(talker.proc)
    assert rec.returncode == -signal.SIGKILL
    info = run_cli("bag", "info", str(out))
    assert info.returncode == 2  # damaged: said so, and read anyway
    assert "without the MCAP footer" in info.stderr and "killed_0.mcap: at byte" in info.stderr
    assert "Traceback" not in info.stderr
    count = int(info.stdout.split("| Count: ")[1].split()[0])
    assert count >= flushed >= 50  # everything flushed before the kill is kept
    # metadata.yaml was kept up to date while recording
    meta = (out / "metadata.yaml").read_text()
    assert "killed_0.mcap" in meta and "/joint_states" in meta
    # the messages read are whole: each one decodes
    from robomodel.bag import open_bag

    bag = open_bag(out)
    states = [deserialize(m.data, JointState) for m in bag.messages()]
    assert len(states) == count
    positions = [s.position[0] for s in states]
    assert positions == sorted(positions)  # in order, none lost within what was kept
