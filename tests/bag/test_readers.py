"""Reading bags that rosbags wrote (rosbag2 with MCAP or SQLite 3, ROS 1 ``.bag``): the
summary and the messages are what the writer put in, in-process.

rosbags is an independent writer here: it names its files, numbers its connections and writes
its metadata its own way, and the reader must find the topics, types, counts, formats,
definitions, times and bytes all the same.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import pytest

from robomodel.bag import McapFolderWriter, open_bag
from robomodel.bag.exceptions import BagFormatError
from robomodel.bag.model import Storage
from robomodel.runtime.msg import String, serialize
from robomodel.runtime.qos import Durability, QoSProfile

rosbag2 = pytest.importorskip("rosbags.rosbag2")
rosbag1 = pytest.importorskip("rosbags.rosbag1")
typesys = pytest.importorskip("rosbags.typesys")
HUMBLE = typesys.get_typestore(typesys.Stores.ROS2_HUMBLE)
NOETIC = typesys.get_typestore(typesys.Stores.ROS1_NOETIC)
STRING, INT32 = "std_msgs/msg/String", "std_msgs/msg/Int32"

# (topic, type, value, log time [ns]) in the order written: the times are not sorted by topic
WRITTEN = [
    ("/chatter", STRING, "hello", 1_000_000_000),
    ("/count", INT32, 7, 1_500_000_000),
    ("/chatter", STRING, "wörld", 2_000_000_000),
    ("/count", INT32, -8, 2_250_000_000),
    ("/chatter", STRING, "", 3_000_000_000),
]


def _rosbag2(folder: Path, plugin: Any) -> list[bytes]:
    """The bag rosbags writes; the payloads in written order."""
    payloads = []
    with rosbag2.Writer(folder, version=9, storage_plugin=plugin) as writer:
        connections = {
            STRING: writer.add_connection("/chatter", STRING, typestore=HUMBLE),
            INT32: writer.add_connection("/count", INT32, typestore=HUMBLE),
        }
        for _, type_name, value, stamp in WRITTEN:
            data = bytes(HUMBLE.serialize_cdr(HUMBLE.types[type_name](data=value), type_name))
            writer.write(connections[type_name], stamp, data)
            payloads.append(data)
    return payloads


def _rosbag1(path: Path) -> list[bytes]:
    payloads = []
    with rosbag1.Writer(path) as writer:
        connections = {
            STRING: writer.add_connection("/chatter", STRING, typestore=NOETIC),
            INT32: writer.add_connection("/count", INT32, typestore=NOETIC),
        }
        for _, type_name, value, stamp in WRITTEN:
            data = bytes(NOETIC.serialize_ros1(NOETIC.types[type_name](data=value), type_name))
            writer.write(connections[type_name], stamp, data)
            payloads.append(data)
    return payloads


@pytest.mark.parametrize(
    ("plugin", "storage", "suffix", "store"),
    [
        ("MCAP", Storage.MCAP, ".mcap", HUMBLE),
        ("SQLITE3", Storage.SQLITE3, ".db3", HUMBLE),
        ("ROS1", Storage.ROS1, ".bag", NOETIC),
    ],
)
def test_summary_and_messages_are_what_rosbags_wrote(
    tmp_path: Path, plugin: str, storage: Storage, suffix: str, store: Any
) -> None:
    if plugin == "ROS1":
        path = tmp_path / "run.bag"
        payloads = _rosbag1(path)
        files = (path,)
    else:
        path = tmp_path / "run"
        payloads = _rosbag2(path, getattr(rosbag2.StoragePlugin, plugin))
        files = tuple(sorted(path.glob(f"*{suffix}")))
        assert len(files) == 1
    bag = open_bag(path)
    assert (bag.path, bag.storage, bag.files) == (path, storage, files)
    summary = bag.summary()
    assert summary.path == str(path) and summary.storage is storage
    assert summary.files == tuple(str(f) for f in files)
    assert summary.size_bytes == sum(f.stat().st_size for f in files) > 0
    assert (summary.start_ns, summary.end_ns) == (1_000_000_000, 3_000_000_000)
    assert summary.duration_ns == 2_000_000_000
    assert summary.message_count == 5
    assert summary.damage == ()
    topics = {t.name: t for t in summary.topics}
    assert set(topics) == {"/chatter", "/count"}
    assert (topics["/chatter"].type, topics["/chatter"].count) == (STRING, 3)
    assert (topics["/count"].type, topics["/count"].count) == (INT32, 2)
    fmt = "ros1" if plugin == "ROS1" else "cdr"
    assert {t.serialization_format for t in topics.values()} == {fmt}
    version = 1 if plugin == "ROS1" else 2
    for name, type_name in (("/chatter", STRING), ("/count", INT32)):
        expected = store.generate_msgdef(type_name, ros_version=version)[0]
        assert topics[name].definition.strip() == expected.strip(), name
    assert not any(t.latched for t in topics.values())

    messages = list(bag.messages())
    assert [(m.topic, m.type, m.log_time_ns) for m in messages] == [
        (topic, type_name, stamp) for topic, type_name, _, stamp in WRITTEN
    ]
    assert [m.data for m in messages] == payloads
    if plugin != "MCAP":  # one time per message in rosbags' readers
        assert all(m.publish_time_ns == m.log_time_ns for m in messages)
    counts = [(m.topic, m.log_time_ns) for m in bag.messages(["/count"])]
    assert counts == [("/count", 1_500_000_000), ("/count", 2_250_000_000)]
    assert list(bag.messages(["/nothing"])) == []
    assert list(bag.messages([])) == []
    assert bag.damage == []


def test_an_mcap_file_alone_and_a_folder_without_metadata(tmp_path: Path) -> None:
    folder = tmp_path / "run"
    _rosbag2(folder, rosbag2.StoragePlugin.MCAP)
    (file,) = folder.glob("*.mcap")
    alone = open_bag(file)
    assert (alone.storage, alone.files) == (Storage.MCAP, (file,))
    summary = alone.summary()
    assert (summary.message_count, summary.ros_distro, summary.path) == (5, "", str(file))
    assert summary.size_bytes == file.stat().st_size
    (folder / "metadata.yaml").unlink()
    second = folder / "z_second.mcap"
    second.write_bytes(file.read_bytes())
    bag = open_bag(folder)
    assert (bag.storage, bag.files) == (Storage.MCAP, (file, second))  # sorted by name
    assert bag.summary().message_count == 10
    assert len(list(bag.messages(["/chatter"]))) == 6


def test_a_missing_piece_is_damage_and_the_rest_is_read(tmp_path: Path) -> None:
    folder = tmp_path / "run"
    _rosbag2(folder, rosbag2.StoragePlugin.MCAP)
    metadata = folder / "metadata.yaml"
    (file,) = folder.glob("*.mcap")
    text = metadata.read_text()
    assert f"- {file.name}" in text
    metadata.write_text(text.replace(f"- {file.name}", f"- {file.name}\n  - gone.mcap"))
    bag = open_bag(folder)
    assert bag.files == (file, folder / "gone.mcap")
    summary = bag.summary()
    assert summary.message_count == 5
    assert summary.size_bytes == file.stat().st_size
    assert [str(d) for d in summary.damage] == [
        f"{folder / 'gone.mcap'}: listed in metadata.yaml but missing"
    ]
    assert [str(d) for d in bag.damage] == [str(d) for d in summary.damage]
    assert len(list(bag.messages())) == 5


def test_an_empty_ros1_bag_has_no_time_span(tmp_path: Path) -> None:
    path = tmp_path / "empty.bag"
    with rosbag1.Writer(path) as writer:
        writer.add_connection("/chatter", STRING, typestore=NOETIC)
    summary = open_bag(path).summary()
    assert (summary.start_ns, summary.end_ns, summary.message_count) == (0, 0, 0)
    assert [(t.name, t.count) for t in summary.topics] == [("/chatter", 0)]


def test_offered_qos_from_the_recording(tmp_path: Path) -> None:
    folder = tmp_path / "latched"
    writer = McapFolderWriter(folder)
    latched = QoSProfile(depth=1, durability=Durability.TRANSIENT_LOCAL)
    writer.add_topic("/robot_description", String, (latched,))
    writer.add_topic("/chatter", String, (QoSProfile(),))
    writer.write("/robot_description", serialize(String("<robot/>")), 5, 5)
    writer.write("/chatter", serialize(String("hi")), 6, 6)
    writer.close()
    topics = {t.name: t for t in open_bag(folder).summary().topics}
    assert topics["/robot_description"].latched and not topics["/chatter"].latched
    assert topics["/robot_description"].offered_qos[0].durability is Durability.TRANSIENT_LOCAL
    # the single file keeps the QoS in its channel's metadata
    (file,) = folder.glob("*.mcap")
    alone = {t.name: t for t in open_bag(file).summary().topics}
    assert alone["/robot_description"].latched and not alone["/chatter"].latched


def _refusal(path: Path) -> str:
    with pytest.raises(BagFormatError) as refused:
        open_bag(path).summary()
    return str(refused.value)


def test_what_is_not_a_bag_is_refused_in_one_line(tmp_path: Path) -> None:
    assert _refusal(tmp_path / "nothing") == f"{tmp_path / 'nothing'}: no such file or directory"
    empty = tmp_path / "empty"
    empty.mkdir()
    assert _refusal(empty) == f"{empty}: not a bag: no metadata.yaml, .mcap or .db3 file"
    text = tmp_path / "notes.txt"
    text.write_text("#ROSBAG V1.2\nnot a bag at all\n")
    assert _refusal(text) == (
        f"{text}: at byte 0: not a bag (neither an MCAP file, a ROS 1 bag nor a rosbag2 folder)"
    )
    folder = tmp_path / "sqlite"
    _rosbag2(folder, rosbag2.StoragePlugin.SQLITE3)
    (db3,) = folder.glob("*.db3")
    assert _refusal(db3) == f"{db3}: a SQLite 3 bag is read as its folder (metadata.yaml)"
    (folder / "metadata.yaml").unlink()
    assert open_bag(folder).storage is Storage.SQLITE3  # found by its .db3 file
    broken = tmp_path / "broken.bag"
    broken.write_bytes(b"#ROSBAG V2.0\n" + b"\x00" * 64)
    refusal = _refusal(broken)
    assert refusal.startswith(f"{broken}: cannot be read: ")
    with pytest.raises(BagFormatError, match="cannot be read"):
        list(open_bag(broken).messages())


# -- damaged MCAP files, read record by record (bag._mcap_reader) ---------------------------

PER_CHUNK, CHUNKS = 3, 3


def _chunked(folder: Path) -> tuple[Path, list[int]]:
    """An MCAP file of CHUNKS chunks of PER_CHUNK /chatter messages; the chunks' offsets."""
    from mcap.reader import make_reader

    writer = McapFolderWriter(folder, flush_period_s=1e9)
    writer.add_topic("/chatter", String, ())
    for k in range(CHUNKS * PER_CHUNK):
        writer.write("/chatter", serialize(String(f"m{k}")), 1_000 + k, 2_000 + k)
        if (k + 1) % PER_CHUNK == 0:
            writer.flush()
    writer.close()
    (path,) = folder.glob("*.mcap")
    with path.open("rb") as handle:
        summary = make_reader(handle).get_summary()
    assert summary is not None
    return path, sorted(c.chunk_start_offset for c in summary.chunk_indexes)


def _scan(path: Path) -> tuple[list[str], list[str], list[Any]]:
    """The messages' texts, the damage notes (with offsets) and the channels seen."""
    from robomodel.bag._mcap_reader import scan_mcap
    from robomodel.bag.model import Damage
    from robomodel.runtime.msg import deserialize

    damage: list[Damage] = []
    channels: list[Any] = []
    texts = [deserialize(m.data, String).data for m in scan_mcap(path, damage, channels.append)]
    return texts, [str(d) for d in damage], channels


def _edit(path: Path, offset: int, new: bytes) -> None:
    data = bytearray(path.read_bytes())
    data[offset : offset + len(new)] = new
    path.write_bytes(bytes(data))


def test_a_sound_mcap_file_gives_its_messages_times_and_schema(tmp_path: Path) -> None:
    from robomodel.bag._mcap_reader import scan_mcap

    path, offsets = _chunked(tmp_path / "b")
    assert len(offsets) == CHUNKS
    texts, damage, channels = _scan(path)
    assert texts == [f"m{k}" for k in range(CHUNKS * PER_CHUNK)] and damage == []
    (channel,) = channels  # the summary repeats it: given once
    assert (channel.topic, channel.type, channel.message_encoding) == ("/chatter", STRING, "cdr")
    assert channel.definition == "string data\n" or channel.definition.startswith("string data")
    assert "offered_qos_profiles" in channel.metadata
    first = next(scan_mcap(path, []))
    assert (first.topic, first.type, first.log_time_ns, first.publish_time_ns) == (
        "/chatter", STRING, 1_000, 2_000,
    )  # fmt: skip


def test_a_cut_file_is_read_up_to_the_cut_and_says_where(tmp_path: Path) -> None:
    path, offsets = _chunked(tmp_path / "b")
    whole = path.read_bytes()
    last = offsets[-1]
    path.write_bytes(whole[: last + 40])  # inside the last chunk
    texts, damage, _ = _scan(path)
    assert texts == [f"m{k}" for k in range((CHUNKS - 1) * PER_CHUNK)]
    length = int.from_bytes(whole[last + 1 : last + 9], "little")
    assert damage == [
        f"{path}: at byte {last}: truncated chunk: {length} bytes declared, 31 present"
    ]
    path.write_bytes(whole[: last + 5])  # inside the record's header
    assert _scan(path)[1] == [f"{path}: at byte {last}: truncated record header (5 of 9 bytes)"]
    path.write_bytes(whole[:last])  # between records: the footer never came
    assert _scan(path)[1] == [
        f"{path}: at byte {last}: file ends without the MCAP footer (the recording was not closed)"
    ]
    end_of_chunks = last + 9 + int.from_bytes(whole[last + 1 : last + 9], "little")
    opcode = whole[end_of_chunks]
    path.write_bytes(whole[: end_of_chunks + 12])  # a record after the chunks, cut
    declared = int.from_bytes(whole[end_of_chunks + 1 : end_of_chunks + 9], "little")
    assert _scan(path)[1] == [
        f"{path}: at byte {end_of_chunks}: truncated record (opcode 0x{opcode:02x}): "
        f"{declared} bytes declared, 3 present"
    ]


def test_a_chunk_failing_its_crc_is_skipped_and_the_rest_read(tmp_path: Path) -> None:
    path, offsets = _chunked(tmp_path / "b")
    data = path.read_bytes()
    second = offsets[1]
    _edit(path, second + 100, bytes([data[second + 100] ^ 0xFF]))
    texts, damage, _ = _scan(path)
    assert texts == [f"m{k}" for k in range(CHUNKS * PER_CHUNK) if k // PER_CHUNK != 1]
    assert len(damage) == 1
    assert damage[0].startswith(f"{path}: at byte {second}: chunk fails its CRC (")
    assert damage[0].endswith("); its messages are skipped")


# a chunk record: opcode, length, start and end time, then the uncompressed size (the second
# chunk: the first holds the schema and the channel, without which nothing after it is read)
_SIZE_AT = 1 + 8 + 8 + 8


def test_a_chunk_declaring_too_much_is_refused_before_it_is_read(tmp_path: Path) -> None:
    from robomodel.bag._mcap_reader import MAX_CHUNK_RATIO

    path, offsets = _chunked(tmp_path / "b")
    size = path.stat().st_size
    _edit(path, offsets[1] + _SIZE_AT, (size * MAX_CHUNK_RATIO + 1).to_bytes(8, "little"))
    with pytest.raises(BagFormatError) as refused:
        _scan(path)
    assert str(refused.value) == (
        f"{path}: at byte {offsets[1]}: a chunk declares {size * MAX_CHUNK_RATIO + 1} bytes "
        f"uncompressed; at most {size * MAX_CHUNK_RATIO} are read (256 MiB, and 1000 times the "
        "file's size): a decompression bomb or a damaged file"
    )
    # exactly the limit is read (and found to be short)
    _edit(path, offsets[1] + _SIZE_AT, (size * MAX_CHUNK_RATIO).to_bytes(8, "little"))
    texts, damage, _ = _scan(path)
    assert texts == [f"m{k}" for k in range(CHUNKS * PER_CHUNK) if k // PER_CHUNK != 1]
    assert damage[0].startswith(f"{path}: at byte {offsets[1]}: chunk expands to only ")


def test_a_chunk_shorter_or_longer_than_it_declares_is_skipped(tmp_path: Path) -> None:
    path, offsets = _chunked(tmp_path / "b")
    declared = int.from_bytes(path.read_bytes()[offsets[1] + _SIZE_AT :][:8], "little")
    _edit(path, offsets[1] + _SIZE_AT, (declared + 10).to_bytes(8, "little"))
    texts, damage, _ = _scan(path)
    assert texts == [f"m{k}" for k in range(CHUNKS * PER_CHUNK) if k // PER_CHUNK != 1]
    assert damage == [
        f"{path}: at byte {offsets[1]}: chunk expands to only {declared} of the "
        f"{declared + 10} bytes it declares; its messages are skipped"
    ]
    _edit(path, offsets[1] + _SIZE_AT, (declared - 1).to_bytes(8, "little"))
    assert _scan(path)[1] == [
        f"{path}: at byte {offsets[1]}: chunk expands beyond the {declared - 1} bytes it "
        "declares; its messages are skipped"
    ]


def test_not_an_mcap_file_is_refused_at_byte_0(tmp_path: Path) -> None:
    path = tmp_path / "x.mcap"
    path.write_bytes(b"\x89MCAP1\r\n" + bytes(100))
    with pytest.raises(BagFormatError) as refused:
        _scan(path)
    assert str(refused.value) == f"{path}: at byte 0: not an MCAP file (bad magic)"


def _foreign_mcap(path: Path, compression: str, *, schema_data: bytes = b"string data\n") -> None:
    """An MCAP file as a writer other than ROS 2's makes it: compressed chunks, channels
    without metadata, one without a schema and one without messages."""
    from mcap.writer import CompressionType, Writer

    with path.open("wb") as handle:
        writer = Writer(handle, compression=CompressionType[compression], chunk_size=64)
        writer.start()
        schema = writer.register_schema(STRING, "ros2msg", schema_data)
        chatter = writer.register_channel("/chatter", "cdr", schema, {})
        raw = writer.register_channel("/raw", "cdr", 0, {})
        writer.register_channel("/quiet", "cdr", schema, {})
        for k in range(6):
            data = serialize(String(f"z{k}"))
            writer.add_message(chatter, 10 + k, data, 20 + k)
        writer.add_message(raw, 99, serialize(String("raw")), 99)
        writer.finish()


@pytest.mark.parametrize("compression", ["ZSTD", "LZ4", "NONE"])
def test_compressed_chunks_and_foreign_channels(tmp_path: Path, compression: str) -> None:
    path = tmp_path / "foreign.mcap"
    _foreign_mcap(path, compression)
    from robomodel.bag._mcap_reader import scan_mcap
    from robomodel.bag.model import Damage
    from robomodel.runtime.msg import deserialize

    found: list[Damage] = []
    seen: list[Any] = []
    messages = list(scan_mcap(path, found, seen.append))
    assert [deserialize(m.data, String).data for m in messages if m.topic == "/chatter"] == [
        f"z{k}" for k in range(6)
    ]
    assert found == []
    by_topic = {c.topic: c for c in seen}
    assert (by_topic["/chatter"].type, by_topic["/chatter"].definition) == (STRING, "string data\n")
    assert (by_topic["/raw"].type, by_topic["/raw"].definition) == ("", "")
    summary = open_bag(path).summary()
    topics = {t.name: t for t in summary.topics}
    assert (topics["/quiet"].count, topics["/raw"].count, topics["/chatter"].count) == (0, 1, 6)
    assert all(t.offered_qos == () for t in topics.values())


def test_damaged_compressed_chunks_are_skipped_and_named(tmp_path: Path) -> None:
    from mcap.reader import make_reader

    path = tmp_path / "z.mcap"
    _foreign_mcap(path, "ZSTD")
    with path.open("rb") as handle:
        summary = make_reader(handle).get_summary()
    assert summary is not None
    chunk = sorted(summary.chunk_indexes, key=lambda c: c.chunk_start_offset)[1]
    data = bytearray(path.read_bytes())
    at = chunk.chunk_start_offset + chunk.chunk_length - 4  # the zstd frame's checksum
    data[at : at + 4] = bytes(4)
    path.write_bytes(bytes(data))
    texts, damage, _ = _scan(path)
    assert len(damage) == 1
    assert damage[0].startswith(f"{path}: at byte {chunk.chunk_start_offset}: chunk does not ")
    assert damage[0].endswith("; its messages are skipped")
    assert 0 < len(texts) < 7


def test_schema_text_that_is_not_utf8_is_kept_readable(tmp_path: Path) -> None:
    path = tmp_path / "s.mcap"
    _foreign_mcap(path, "NONE", schema_data=b"string data # \xff\n")
    _, damage, channels = _scan(path)
    assert damage == []
    assert channels[0].definition == "string data # \ufffd\n"


def test_a_file_of_the_magic_alone_is_named_at_its_first_record(tmp_path: Path) -> None:
    from robomodel.bag._mcap_reader import MAGIC

    path = tmp_path / "m.mcap"
    path.write_bytes(MAGIC)
    assert _scan(path)[1] == [f"{path}: at byte 8: unreadable record (EndOfFile: )"]


def test_bag_metadata_s_distribution_and_a_missing_reader(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    import sys

    import yaml as pyyaml

    from robomodel.errors import MissingDependencyError

    for plugin in (rosbag2.StoragePlugin.MCAP, rosbag2.StoragePlugin.SQLITE3):
        folder = tmp_path / plugin.name
        _rosbag2(folder, plugin)
        metadata = folder / "metadata.yaml"
        info = pyyaml.safe_load(metadata.read_text())
        info["rosbag2_bagfile_information"]["ros_distro"] = "jazzy"
        metadata.write_text(pyyaml.safe_dump(info))
        assert open_bag(folder).summary().ros_distro == "jazzy", plugin
    fifo = tmp_path / "pipe.bag"
    os.mkfifo(fifo)
    with pytest.raises(BagFormatError) as refused:
        open_bag(fifo)
    assert "cannot read bag file: it is a named pipe" in str(refused.value)
    monkeypatch.setitem(sys.modules, "mcap.stream_reader", None)
    with pytest.raises(MissingDependencyError, match="reading MCAP bags"):
        open_bag(tmp_path / "MCAP").summary()


def test_each_decompressor_and_a_missing_one(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """zstd through whichever module is there (Python 3.14's, the backport, mcap's
    ``zstandard``), lz4 through ``lz4.frame``; a missing one is named with what it is for."""
    import sys

    from robomodel.errors import MissingDependencyError

    zstd, lz4 = tmp_path / "z.mcap", tmp_path / "l.mcap"
    _foreign_mcap(zstd, "ZSTD")
    _foreign_mcap(lz4, "LZ4")
    for name in ("compression.zstd", "backports.zstd"):
        monkeypatch.setitem(sys.modules, name, None)
    texts, damage, _ = _scan(zstd)  # through zstandard's stream reader
    assert damage == [] and texts[:6] == [f"z{k}" for k in range(6)]
    monkeypatch.setitem(sys.modules, "zstandard", None)
    with pytest.raises(MissingDependencyError) as missing:
        _scan(zstd)
    assert "zstandard" in str(missing.value) and "reading zstd-compressed MCAP chunks" in str(
        missing.value
    )
    assert "robomodel[bag]" in str(missing.value)
    monkeypatch.setitem(sys.modules, "lz4.frame", None)
    with pytest.raises(MissingDependencyError, match="reading lz4-compressed MCAP chunks"):
        _scan(lz4)
    monkeypatch.setitem(sys.modules, "mcap.records", None)
    with pytest.raises(MissingDependencyError, match="reading MCAP bags"):
        _scan(lz4)
