"""Hostile bag files: each is refused or read within its
bound, in the process that reads it, with one clear line and no traceback."""

from __future__ import annotations

import contextlib
import io
import random
import struct
import sys
from pathlib import Path

import pytest

from tests.measured import MIB, run_measured

# ``robomodel bag info`` of a small bag peaks near 100 MiB (Python, numpy, mcap, rosbags); a
# bomb that got through would add the gigabytes it declares.
INFO_RSS_BOUND = 400 * MIB


def _zstd_rle_bomb(size: int) -> bytes:
    """A zstd frame of RLE blocks (4 bytes per 128 KiB of zeros) expanding to ``size`` bytes,
    the content size in its header: 66 KB for 2 GiB, as the reproducer of finding 3."""
    block = 128 << 10
    frame = bytearray(struct.pack("<I", 0xFD2FB528) + bytes([0xE0]) + struct.pack("<Q", size))
    blocks = size // block
    for k in range(blocks):
        last = 1 if k == blocks - 1 else 0
        frame += (block << 3 | 1 << 1 | last).to_bytes(3, "little") + b"\x00"
    return bytes(frame)


def _mcap_with_chunk(compression: str, data: bytes, declared: int) -> bytes:
    """An MCAP file with one chunk of ``data`` that says it holds ``declared`` bytes."""
    from mcap.data_stream import RecordBuilder
    from mcap.records import Chunk, DataEnd, Footer, Header

    builder = RecordBuilder()
    Header(profile="ros2", library="bomb").write(builder)
    Chunk(
        message_start_time=0, message_end_time=0, uncompressed_size=declared,
        uncompressed_crc=0, compression=compression, data=data,
    ).write(builder)  # fmt: skip
    DataEnd(data_section_crc=0).write(builder)
    Footer(summary_start=0, summary_offset_start=0, summary_crc=0).write(builder)
    out = io.BytesIO()
    out.write(b"\x89MCAP0\r\n" + builder.end() + b"\x89MCAP0\r\n")
    return out.getvalue()


def _one_error_line(err: str) -> str:
    lines = [line for line in err.splitlines() if line.startswith("robomodel: error:")]
    assert len(lines) == 1 and "Traceback" not in err, err
    return lines[0]


def test_mcap_decompression_bombs_are_refused_within_the_bound(tmp_path: Path) -> None:
    """Finding 3: a 66 KB zstd chunk expanding to 2 GiB (RSS went to 4.2 GB), and an lz4 one,
    declaring their size or lying about it."""
    import lz4.frame

    bomb = tmp_path / "zstd_bomb.mcap"
    bomb.write_bytes(_mcap_with_chunk("zstd", _zstd_rle_bomb(2 << 30), 2 << 30))
    assert bomb.stat().st_size < 70_000
    result = run_measured("bag", "info", str(bomb))
    assert result.code == 2
    assert "a chunk declares 2147483648 bytes uncompressed" in _one_error_line(result.err)
    assert result.peak_rss_bytes < INFO_RSS_BOUND

    zeros = lz4.frame.compress(bytes(64 * MIB))  # 64 MiB in about 260 KB
    for declared, expected in ((2 << 30, "a chunk declares"), (MIB, "chunk expands beyond")):
        liar = tmp_path / f"lz4_{declared}.mcap"
        liar.write_bytes(_mcap_with_chunk("lz4", zeros, declared))
        result = run_measured("bag", "info", str(liar))
        assert result.code == 2 and expected in _one_error_line(result.err)
        assert result.peak_rss_bytes < INFO_RSS_BOUND

    # the ratio to the file's size: 64 MiB from a 260 KB file is within 1000 times; from a
    # file a hundred times smaller it is not
    small = tmp_path / "small.mcap"
    small.write_bytes(_mcap_with_chunk("zstd", _zstd_rle_bomb(4 * MIB), 4 * MIB))
    result = run_measured("bag", "info", str(small))
    assert "times the file's size" in _one_error_line(result.err)


@pytest.mark.parametrize("codec", ["lz4", "zstd", "zstandard"])
def test_a_chunk_that_expands_beyond_its_declared_size_is_never_held_whole(
    codec: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A chunk declaring 64 KiB whose stream expands to 32 MiB is damage, found by reading at
    most one byte past what it declares: the reader's allocations stay far below the 32 MiB
    (measured with tracemalloc, in this process). ``zstandard`` is the fallback without the
    zstd module of Python 3.14 or its backport."""
    import tracemalloc

    import lz4.frame

    from robomodel.bag._mcap_reader import scan_mcap
    from robomodel.bag.model import Damage

    declared = 64 << 10
    data = lz4.frame.compress(bytes(32 * MIB)) if codec == "lz4" else _zstd_rle_bomb(32 * MIB)
    if codec == "zstandard":
        monkeypatch.setitem(sys.modules, "compression.zstd", None)  # None: ImportError
        monkeypatch.setitem(sys.modules, "backports.zstd", None)
    liar = tmp_path / f"{codec}.mcap"
    liar.write_bytes(_mcap_with_chunk(codec.replace("zstandard", "zstd"), data, declared))
    damage: list[Damage] = []
    tracemalloc.start()
    try:
        assert list(scan_mcap(liar, damage)) == []
        _, peak_bytes = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert [d.reason for d in damage] == [
        f"chunk expands beyond the {declared} bytes it declares; its messages are skipped"
    ]
    assert peak_bytes < 4 * MIB


_LAUGHS = "\n".join(
    ["rosbag2_bagfile_information:", "  storage_identifier: mcap", '  a0: &a0 ["lol"]']
    + [f"  a{k}: &a{k} [{', '.join([f'*a{k - 1}'] * 9)}]" for k in range(1, 10)]
    + ["  relative_file_paths: *a9", ""]
)


def test_metadata_yaml_bombs_are_refused_within_the_bound(tmp_path: Path) -> None:
    """Finding 5: an alias bomb of about 600 bytes hung ``bag info``, 3 million
    relative_file_paths hung it too, nesting 50,000 deep gave a RecursionError traceback."""
    header = "rosbag2_bagfile_information:\n  storage_identifier: mcap\n"
    cases = {
        "laughs": (_LAUGHS, "line 4: a YAML alias (*a0); aliases are not accepted here"),
        "millions": (
            header + "  relative_file_paths:\n" + "  - a.mcap\n" * 3_000_000,
            "31.5 MiB; at most 4 MiB of bag metadata is read",
        ),
        "many": (
            header + "  relative_file_paths:\n" + "  - a.mcap\n" * 10_001,
            "10001 relative_file_paths; a bag has at most 10000",
        ),
        # libyaml's own bound (1,000 levels) is met first in flow style; robomodel's (64) in
        # block style
        "deep": (header + "  x: " + "[" * 50_000 + "]" * 50_000 + "\n", "maximum nesting depth"),
        "deep_block": (
            header + "".join(f"{'  ' * (k + 1)}k:\n" for k in range(100)),
            "nested more than 64 levels deep",
        ),
    }
    assert len(_LAUGHS) < 700
    for name, (text, expected) in cases.items():
        folder = tmp_path / name
        folder.mkdir()
        (folder / "metadata.yaml").write_text(text)
        result = run_measured("bag", "info", str(folder))
        line = _one_error_line(result.err)
        assert result.code == 2 and line.startswith(f"robomodel: error: {folder}/metadata.yaml")
        assert expected in line, line
        assert result.peak_rss_bytes < INFO_RSS_BOUND


def _sqlite3_bag(folder: Path) -> Path:
    """A SQLite 3 bag of 5 /joint_states and 5 /s messages; returns its database."""
    from robomodel.bag import Sqlite3FolderWriter
    from robomodel.runtime.msg import JointState, String, serialize

    writer = Sqlite3FolderWriter(folder)
    writer.add_topic("/joint_states", JointState, ())
    writer.add_topic("/s", String, ())
    for k in range(5):
        state = JointState(name=["a"], position=[float(k)])
        writer.write("/joint_states", serialize(state), 1_000_000_000 + k, k)
        writer.write("/s", serialize(String("x")), 1_000_000_000 + k, k)
    writer.close()
    return next(folder.glob("*.db3"))


def _sql(db: Path, statement: str) -> None:
    import sqlite3

    with contextlib.closing(sqlite3.connect(db)) as connection:
        connection.execute(statement)
        connection.commit()


def test_sqlite3_bags_that_cannot_be_played_say_so(tmp_path: Path) -> None:
    """Finding 15: a SQLite 3 bag with a garbage type or a dangling topic_id played
    "0 messages", exited 0 and gave no warning."""
    garbage = tmp_path / "garbage"
    _sqlite3_bag(garbage)
    meta = garbage / "metadata.yaml"
    text = meta.read_text().replace("sensor_msgs/msg/JointState", "garbage")
    meta.write_text(text.replace("std_msgs/msg/String", "x/y/z"))
    dangling = tmp_path / "dangling"
    _sql(_sqlite3_bag(dangling), "UPDATE messages SET topic_id = 999")
    partly = tmp_path / "partly"
    _sql(_sqlite3_bag(partly), "UPDATE messages SET topic_id = 999 WHERE topic_id = "
                               "(SELECT id FROM topics WHERE name = '/s')")  # fmt: skip

    expected = {
        garbage: ["not playing /joint_states (garbage)", "not playing /s (x/y/z)"],
        dangling: [
            "/joint_states: the bag lists 5 messages, its storage holds 0 of them",
            "/s: the bag lists 5 messages, its storage holds 0 of them",
        ],
        partly: ["/s: the bag lists 5 messages, its storage holds 0 of them"],
    }
    for bag, warnings in expected.items():
        result = run_measured("bag", "play", str(bag), "--bus", "inproc", "--delay", "0")
        said = [line for line in result.err.splitlines() if line.startswith("robomodel bag:")]
        assert [w for w in warnings if any(w in line for line in said)] == warnings, result.err
        assert len(said) == len(warnings) and "Traceback" not in result.err, result.err
        assert result.peak_rss_bytes < INFO_RSS_BOUND
        if bag is partly:
            assert result.code == 0 and "played 5 messages" in result.err
            continue
        assert result.code == 2
        line = _one_error_line(result.err)
        assert line.startswith(f"robomodel: error: {bag}: none of its 10 messages could be played")


def _mcap_of(path: Path, compression: str, payloads: list[bytes]) -> None:
    """A sound MCAP file with ``payloads`` on /data, in one chunk compressed with
    ``compression``."""
    from mcap.writer import CompressionType, Writer

    with path.open("wb") as stream:
        writer = Writer(stream, compression=CompressionType[compression.upper()],
                        chunk_size=64 * MIB)  # fmt: skip
        writer.start(profile="ros2", library="test")
        schema = writer.register_schema("std_msgs/msg/String", "ros2msg", b"string data")
        channel = writer.register_channel("/data", "cdr", schema)
        for k, payload in enumerate(payloads):
            writer.add_message(channel, log_time=k, data=payload, publish_time=k)
        writer.finish()


ZSTD_MODULES = ("compression.zstd", "backports.zstd", "zstandard")


@pytest.mark.parametrize(
    ("codec", "present"),
    [("zstd", "backports.zstd"), ("zstd", "zstandard"), ("lz4", "lz4.frame")],
)
def test_chunks_of_several_mib_decompress_whole_with_each_codec_module(
    codec: str, present: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Each zstd module alone reads the chunk (the others made missing), in pieces when the
    chunk is larger than one read: two messages of 1.5 MiB come back byte for byte."""
    from robomodel.bag._mcap_reader import scan_mcap
    from robomodel.bag.model import Damage

    payloads = [random.Random(k).randbytes(3 * MIB // 2) for k in (1, 2)]  # incompressible
    path = tmp_path / f"{codec}.mcap"
    _mcap_of(path, codec, payloads)
    for module in ZSTD_MODULES if codec == "zstd" else ():
        if module != present:
            monkeypatch.setitem(sys.modules, module, None)  # None: ImportError
    damage: list[Damage] = []
    assert [m.data for m in scan_mcap(path, damage)] == payloads
    assert damage == []


@pytest.mark.parametrize(
    ("codec", "blocked", "message"),
    [
        ("zstd", ZSTD_MODULES, "reading zstd-compressed MCAP chunks needs the 'zstandard' "
                               "package: pip install 'robomodel[bag]'"),
        ("lz4", ("lz4.frame",), "reading lz4-compressed MCAP chunks needs the 'lz4' package: "
                                "pip install 'robomodel[bag]'"),
    ],
)  # fmt: skip
def test_a_missing_codec_module_names_the_package_and_the_extra(
    codec: str, blocked: tuple[str, ...], message: str, tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
) -> None:  # fmt: skip
    from robomodel.bag._mcap_reader import scan_mcap
    from robomodel.errors import MissingDependencyError

    path = tmp_path / f"{codec}.mcap"
    _mcap_of(path, codec, [b"\x00" * 64])
    for module in blocked:
        monkeypatch.setitem(sys.modules, module, None)
    with pytest.raises(MissingDependencyError) as caught:
        list(scan_mcap(path, []))
    assert str(caught.value) == message
