"""``bag record --max-bag-duration`` / ``--max-bag-size``: a rosbag2 folder of several MCAP files
(``NAME_0.mcap``, ``NAME_1.mcap``, ...) split where rosbag2 splits, with a metadata.yaml listing
each file's span and count (rosbag2's ``files:``), read whole by rosbags' reader in a process
of its own, by ``bag info`` and by ``bag play``."""

from __future__ import annotations

import subprocess
import time
from pathlib import Path

import yaml

from robomodel.bag import open_bag
from robomodel.bag._mcap_writer import MESSAGE_OVERHEAD
from robomodel.runtime import Context
from robomodel.runtime.msg import JointState, deserialize
from tests.conftest import ROBOMODEL, unique_domain
from tests.timing import scaled

from .conftest import Talker, flushed_count, rosbags_read, run_cli, stop

MAX_S = 0.6
MAX_BYTES = 6000


def _file_messages(path: Path) -> list[tuple[str, int, bytes]]:
    from mcap.reader import make_reader

    with path.open("rb") as handle:
        return [
            (channel.topic, message.log_time, message.data)
            for _, channel, message in make_reader(handle).iter_messages(log_time_order=False)
        ]


def _check_metadata(folder: Path) -> list[list[tuple[str, int, bytes]]]:
    """metadata.yaml agrees with the files: names, order, per-file and total counts and spans."""
    info = yaml.safe_load((folder / "metadata.yaml").read_text())["rosbag2_bagfile_information"]
    names = [f"{folder.name}_{i}.mcap" for i in range(len(info["files"]))]
    assert len(names) >= 3
    assert [f["path"] for f in info["files"]] == names == info["relative_file_paths"]
    assert sorted(p.name for p in folder.glob("*.mcap")) == sorted(names)
    pieces = [_file_messages(folder / name) for name in names]
    for entry, messages in zip(info["files"], pieces, strict=True):
        times = [t for _, t, _ in messages]
        assert entry["message_count"] == len(messages) > 0
        assert entry["starting_time"]["nanoseconds_since_epoch"] == min(times)
        assert entry["duration"]["nanoseconds"] == max(times) - min(times)
    everything = [m for piece in pieces for m in piece]
    assert info["message_count"] == len(everything)
    assert sum(t["message_count"] for t in info["topics_with_message_count"]) == len(everything)
    times = [t for _, t, _ in everything]
    assert info["starting_time"]["nanoseconds_since_epoch"] == min(times)
    assert info["duration"]["nanoseconds"] == max(times) - min(times)
    states = [t for topic, t, _ in everything if topic == "/joint_states"]
    assert states == sorted(states)  # the pieces follow each other
    return pieces


def _record(folder: Path, domain: str, *split: str) -> subprocess.Popen[str]:
    return subprocess.Popen(
        [*ROBOMODEL, "bag", "record", "/joint_states", "/robot_description", "-o", str(folder),
         *split, "--domain-id", domain],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
    )  # fmt: skip


def _positions_played(folder: Path, expected: int) -> list[float]:
    domain = unique_domain()
    seen: list[float] = []
    with Context("zenoh", domain_id=int(domain)) as context:
        node = context.create_node("probe")
        node.create_subscription(
            JointState, "/joint_states", lambda m: seen.append(m.position[0]), 1000
        )
        play = subprocess.Popen(
            [*ROBOMODEL, "bag", "play", str(folder), "--rate", "4", "--domain-id", domain],
            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
        )  # fmt: skip
        try:
            deadline = time.monotonic() + scaled(30)
            context.spin(until=lambda: len(seen) >= expected or time.monotonic() > deadline)
            assert play.wait(scaled(15)) == 0
        finally:
            stop(play)
    return seen


def test_split_by_duration_and_size(tmp_path: Path) -> None:
    talker = Talker(tmp_path, period_s=0.01)
    by_time, by_size = tmp_path / "by_time", tmp_path / "by_size"
    recorders = [
        _record(by_time, talker.domain, "--max-bag-duration", str(MAX_S)),
        _record(by_size, talker.domain, "--max-bag-size", str(MAX_BYTES)),
    ]
    try:
        deadline = time.monotonic() + scaled(40)
        while min(map(flushed_count, (by_time, by_size))) < 200 and time.monotonic() < deadline:
            time.sleep(0.1)  # each recorder's metadata.yaml says what it has written so far
        for proc in recorders:
            stop(proc)  # SIGTERM: the files are closed with their indexes
        results = [(r.returncode, r.communicate()[1]) for r in recorders]
    finally:
        for proc in (*recorders, talker.proc):
            stop(proc)
    for code, err in results:
        assert code == 0, err
    assert "by_time/by_time_0.mcap, " in results[0][1]  # the summary names every file

    pieces = _check_metadata(by_time)
    starts = [piece[0][1] for piece in pieces]
    for piece, start, following in zip(pieces, starts, [*starts[1:], None], strict=True):
        assert piece[-1][1] - start < MAX_S * 1e9  # no file spans more than -d
        if following is not None:
            assert following - start >= MAX_S * 1e9  # a file is started only once it is due

    pieces = _check_metadata(by_size)
    for index, piece in enumerate(pieces[:-1]):
        size = (by_size / f"by_size_{index}.mcap").stat().st_size
        assert size >= MAX_BYTES  # full before the next is started
        assert sum(len(data) + MESSAGE_OVERHEAD for _, _, data in piece[:-1]) < MAX_BYTES

    # rosbags (another process) reads every piece, as we wrote them (in time order: it merges)
    import hashlib

    for folder, theirs in zip(
        (by_time, by_size), rosbags_read(tmp_path, by_time, by_size), strict=True
    ):
        ours = [
            [topic, log, hashlib.sha256(data).hexdigest()]
            for piece in _check_metadata(folder)
            for topic, log, data in piece
        ]
        assert theirs["messages"] == sorted(ours, key=lambda m: m[1])
        assert theirs["count"] == len(ours)

    info = run_cli("bag", "info", str(by_size))
    assert info.returncode == 0, info.stderr
    total = sum(len(piece) for piece in pieces)
    assert f"Messages:          {total}\n" in info.stdout
    listed = [str(by_size / f"by_size_{i}.mcap") for i in range(len(pieces))]
    assert "\n                   ".join(listed) in info.stdout  # every file, in order

    recorded = [
        deserialize(m.data, JointState).position[0]
        for m in open_bag(by_time).messages()
        if m.topic == "/joint_states"
    ]
    assert _positions_played(by_time, len(recorded)) == recorded  # every piece, in order
