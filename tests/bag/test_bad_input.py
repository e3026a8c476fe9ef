"""Damaged and foreign input: one clear line naming the file and offset, exit code 2, no
traceback; what can be read is still read by ``info`` and ``play``."""

from __future__ import annotations

import os
from collections.abc import Callable
from pathlib import Path

import pytest

from robomodel.bag import McapFolderWriter, Player, PlayOptions, SplitPolicy, open_bag
from robomodel.runtime import Context, ManualClock
from robomodel.runtime.msg import JointState, serialize
from tests.conftest import ToolResult

PER_CHUNK = 5
CHUNKS = 4


def _write_bag(folder: Path) -> None:
    """CHUNKS chunks of PER_CHUNK /joint_states messages each."""
    writer = McapFolderWriter(folder, flush_period_s=1e9)
    writer.add_topic("/joint_states", JointState, ())
    for k in range(CHUNKS * PER_CHUNK):
        msg = JointState(name=["a"], position=[float(k)])
        writer.write("/joint_states", serialize(msg), 1_000_000_000 + k * 10_000_000, k)
        if (k + 1) % PER_CHUNK == 0:
            writer.flush()
    writer.close()


def _chunk_offsets(path: Path) -> list[int]:
    from mcap.reader import make_reader

    with path.open("rb") as handle:
        summary = make_reader(handle).get_summary()
    assert summary is not None
    return sorted(c.chunk_start_offset for c in summary.chunk_indexes)


def _count(out: str) -> int:
    return int(out.split("| Count: ")[1].split()[0])


@pytest.fixture
def bag(tmp_path: Path) -> Path:
    folder = tmp_path / "good"
    _write_bag(folder)
    return folder


def test_sound_bag_reads_whole(bag: Path, cli: Callable[..., ToolResult]) -> None:
    result = cli("bag", "info", str(bag))
    assert result.code == 0 and result.err == ""
    assert _count(result.out) == CHUNKS * PER_CHUNK
    assert len(_chunk_offsets(bag / "good_0.mcap")) == CHUNKS


def test_not_a_bag(tmp_path: Path, cli: Callable[..., ToolResult]) -> None:
    junk = tmp_path / "notes.bag"
    junk.write_text("hello, not a bag\n")
    result = cli("bag", "info", str(junk))
    assert result.code == 2
    assert result.err.strip() == (
        f"robomodel: error: {junk}: at byte 0: not a bag "
        "(neither an MCAP file, a ROS 1 bag nor a rosbag2 folder)"
    )
    empty = tmp_path / "empty"
    empty.mkdir()
    result = cli("bag", "play", str(empty), "--bus", "inproc")
    assert result.code == 2 and "not a bag: no metadata.yaml" in result.err
    assert "Traceback" not in result.err


def test_truncated_file_is_read_up_to_the_cut(bag: Path, cli: Callable[..., ToolResult]) -> None:
    path = bag / "good_0.mcap"
    last = _chunk_offsets(path)[-1]
    path.write_bytes(path.read_bytes()[: last + 40])  # cut inside the last chunk
    result = cli("bag", "info", str(bag))
    assert result.code == 2
    assert _count(result.out) == (CHUNKS - 1) * PER_CHUNK
    assert f"robomodel: error: {path}: at byte {last}: truncated chunk" in result.err
    assert "Traceback" not in result.err


def test_bad_crc_chunk_is_skipped(bag: Path, cli: Callable[..., ToolResult]) -> None:
    path = bag / "good_0.mcap"
    second = _chunk_offsets(path)[1]
    data = bytearray(path.read_bytes())
    data[second + 120] ^= 0xFF  # a byte of the chunk's message data
    path.write_bytes(bytes(data))
    result = cli("bag", "info", str(bag))
    assert result.code == 2
    assert _count(result.out) == (CHUNKS - 1) * PER_CHUNK
    assert f"{path}: at byte {second}: chunk fails its CRC" in result.err
    # play publishes what is sound: the chunks before and after the bad one
    context = Context(clock=ManualClock())
    seen: list[float] = []
    sub = context.create_node("listener")
    sub.create_subscription(JointState, "/joint_states", lambda m: seen.append(m.position[0]), 100)
    damaged = open_bag(bag)
    player = Player(context, damaged, PlayOptions(rate=100.0))
    player.play()
    context.spin(duration_s=0.1)
    expected = [float(k) for k in range(CHUNKS * PER_CHUNK) if k // PER_CHUNK != 1]
    assert seen == expected
    assert any("chunk fails its CRC" in str(d) for d in damaged.damage)


@pytest.mark.parametrize(
    ("options", "message"),
    [
        (["-b", "-5"], "--max-bag-size must be 0 (no splitting) or positive, got -5"),
        (["-d", "nan"], "--max-bag-duration must be 0 (no splitting) or positive, got nan"),
        (["-d", "inf"], "--max-bag-duration must be 0 (no splitting) or positive, got inf"),
        (["-s", "sqlite3", "-d", "1"], "--max-bag-size and --max-bag-duration need --storage mcap"),
    ],
)
def test_bad_split_options(
    tmp_path: Path, cli: Callable[..., ToolResult], options: list[str], message: str
) -> None:
    out = tmp_path / "never"
    result = cli("bag", "record", "-a", "-o", str(out), *options, "--bus", "inproc")
    assert result.code == 2
    assert result.err == f"robomodel: error: {message}\n"
    assert not out.exists()  # refused before anything is created


def test_zero_split_limits_mean_no_splitting() -> None:
    from robomodel.cli.bag import _split_policy
    from robomodel.cli.main import build_parser

    args = build_parser("bag").parse_args(["bag", "record", "-a", "-b", "0", "-d", "0"])
    assert not _split_policy(args).splits  # as ros2 bag record's defaults
    args = build_parser("bag").parse_args(["bag", "record", "-a", "-b", "100", "-d", "0.5"])
    assert _split_policy(args) == SplitPolicy(100, 500_000_000)


def test_devices_fifos_and_paths_outside_the_folder_are_refused(
    tmp_path: Path, cli: Callable[..., ToolResult]
) -> None:
    fifo = tmp_path / "pipe.mcap"
    os.mkfifo(fifo)
    done = cli("bag", "info", str(fifo))
    assert done.code == 2 and "named pipe (FIFO); only regular files are read" in done.err
    device = tmp_path / "device"
    device.mkdir()
    (device / "metadata.yaml").symlink_to("/dev/zero")
    done = cli("bag", "info", str(device))
    assert done.code == 2 and "metadata.yaml: cannot read bag metadata" in done.err
    escaping = tmp_path / "escaping"
    escaping.mkdir()
    (escaping / "metadata.yaml").write_text(
        "rosbag2_bagfile_information:\n  storage_identifier: mcap\n"
        "  relative_file_paths: [../../../dev/zero]\n"
    )
    done = cli("bag", "info", str(escaping))
    assert done.code == 2 and "is outside the bag folder" in done.err
