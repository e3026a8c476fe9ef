"""Opening bags for reading: rosbag2 folders (MCAP or SQLite 3), single ``.mcap`` files and
ROS 1 ``.bag`` files, whoever wrote them (robomodel, ``ros2 bag``, ``rosbag``).

MCAP is read with Foxglove's ``mcap`` library record by record, so that damaged files are read
up to the damage (see :mod:`._mcap_reader`); SQLite 3 and ROS 1 bags with rosbags' readers.
Problems that leave the rest readable are collected in :attr:`Bag.damage`; a file that is not
a bag at all raises :class:`BagFormatError`.
"""

from __future__ import annotations

import contextlib
import sys
from collections.abc import Collection, Iterator
from pathlib import Path
from typing import Any

import yaml

from robomodel._files import UserFileError, check_user_file
from robomodel._yaml_bounded import YamlNestingError, load_yaml_data
from robomodel.bag._deps import require
from robomodel.bag._mcap_reader import McapChannel, scan_mcap
from robomodel.bag._metadata import Metadata, qos_from_dict, read_metadata
from robomodel.bag.exceptions import BagFormatError
from robomodel.bag.model import BagMessage, BagSummary, Damage, Storage, TopicSummary
from robomodel.runtime.qos import QoSProfile

__all__ = ["Bag", "open_bag"]

ROS1_MAGIC = b"#ROSBAG V2.0\n"
MCAP_MAGIC = b"\x89MCAP0\r\n"
SQLITE_MAGIC = b"SQLite format 3\x00"


def _regular(path: Path) -> None:
    """A bag file must be a regular file (any size): not a FIFO or a device to read forever."""
    try:
        check_user_file(path, what="bag file", limit=sys.maxsize)
    except UserFileError as exc:
        raise BagFormatError(str(path), exc.reason) from None


def _magic(path: Path) -> bytes:
    _regular(path)
    try:
        with path.open("rb") as handle:
            return handle.read(16)
    except OSError as exc:
        raise BagFormatError(str(path), f"cannot be read ({exc.strerror})") from None


def _detect(path: Path) -> tuple[Storage, tuple[Path, ...], Metadata | None]:
    if not path.exists():
        raise BagFormatError(str(path), "no such file or directory")
    if path.is_dir():
        metadata = read_metadata(path) if (path / "metadata.yaml").exists() else None
        if metadata is not None and metadata.files:
            pieces = tuple(path / f for f in metadata.files)
            for piece in pieces:
                if piece.exists():  # a missing piece is reported by the reader, with the rest
                    _regular(piece)
            return metadata.storage, pieces, metadata
        for storage, pattern in ((Storage.MCAP, "*.mcap"), (Storage.SQLITE3, "*.db3")):
            files = tuple(sorted(path.glob(pattern)))
            if files:
                return storage, files, metadata
        raise BagFormatError(str(path), "not a bag: no metadata.yaml, .mcap or .db3 file")
    head = _magic(path)
    if head.startswith(ROS1_MAGIC):
        return Storage.ROS1, (path,), None
    if head.startswith(MCAP_MAGIC):
        return Storage.MCAP, (path,), None
    if head.startswith(SQLITE_MAGIC):
        raise BagFormatError(str(path), "a SQLite 3 bag is read as its folder (metadata.yaml)")
    raise BagFormatError(
        str(path), "not a bag (neither an MCAP file, a ROS 1 bag nor a rosbag2 folder)", offset=0
    )


def _channel_qos(channel: McapChannel) -> tuple[QoSProfile, ...]:
    text = channel.metadata.get("offered_qos_profiles", "")
    try:
        entries = load_yaml_data(text, what=channel.topic) if text.strip() else []
    except (yaml.YAMLError, YamlNestingError):
        return ()
    return tuple(qos_from_dict(e) for e in entries or () if isinstance(e, dict))


class _Tally:
    """Counts and time span per topic, as messages go by."""

    def __init__(self) -> None:
        self.types: dict[str, str] = {}
        self.formats: dict[str, str] = {}
        self.definitions: dict[str, str] = {}
        self.qos: dict[str, tuple[QoSProfile, ...]] = {}
        self.counts: dict[str, int] = {}
        self.start = 0
        self.end = 0
        self.total = 0

    def channel(self, channel: McapChannel) -> None:
        self.types.setdefault(channel.topic, channel.type)
        self.formats.setdefault(channel.topic, channel.message_encoding)
        self.definitions.setdefault(channel.topic, channel.definition)
        self.qos.setdefault(channel.topic, _channel_qos(channel))
        self.counts.setdefault(channel.topic, 0)

    def message(self, message: BagMessage) -> None:
        self.counts[message.topic] = self.counts.get(message.topic, 0) + 1
        self.start = message.log_time_ns if not self.total else min(self.start, message.log_time_ns)
        self.end = max(self.end, message.log_time_ns)
        self.total += 1

    def topics(self, qos: dict[str, tuple[QoSProfile, ...]]) -> tuple[TopicSummary, ...]:
        return tuple(
            TopicSummary(
                name,
                self.types[name],
                self.counts[name],
                self.formats[name],
                qos.get(name) or self.qos.get(name, ()),
                self.definitions.get(name, ""),
            )
            for name in self.types
        )


class Bag:
    """A bag opened for reading; see :func:`open_bag`."""

    def __init__(self, path: str | Path) -> None:
        self.path = Path(path)
        self.storage, self.files, self._metadata = _detect(self.path)
        self.damage: list[Damage] = []

    def _qos(self) -> dict[str, tuple[QoSProfile, ...]]:
        return dict(self._metadata.qos) if self._metadata else {}

    def summary(self) -> BagSummary:
        """Topics, counts, time span and size. MCAP files are read through (checking CRCs)."""
        if self.storage is Storage.MCAP:
            return self._mcap_summary()
        return self._rosbags_summary()

    def _mcap_summary(self) -> BagSummary:
        tally = _Tally()
        damage: list[Damage] = []
        for file in self.files:
            if not file.exists():
                damage.append(Damage(str(file), None, "listed in metadata.yaml but missing"))
                continue
            for message in scan_mcap(file, damage, tally.channel):
                tally.message(message)
        self.damage.extend(damage)
        return BagSummary(
            str(self.path), self.storage, tuple(str(f) for f in self.files), self._size(),
            tally.start, tally.end, tally.total, tally.topics(self._qos()),
            self._metadata.ros_distro if self._metadata else "", tuple(damage),
        )  # fmt: skip

    def _size(self) -> int:
        return sum(f.stat().st_size for f in self.files if f.exists())

    def _rosbags_summary(self) -> BagSummary:
        with self._rosbags_reader() as reader:
            counts: dict[str, int] = {}
            types: dict[str, str] = {}
            formats: dict[str, str] = {}
            definitions: dict[str, str] = {}
            for conn in reader.connections:
                counts[conn.topic] = counts.get(conn.topic, 0) + conn.msgcount
                types.setdefault(conn.topic, conn.msgtype)
                ext_format = getattr(conn.ext, "serialization_format", "ros1")
                formats.setdefault(conn.topic, ext_format)
                definitions.setdefault(conn.topic, getattr(conn.msgdef, "data", "") or "")
            qos = self._qos()
            topics = tuple(
                TopicSummary(t, types[t], counts[t], formats[t], qos.get(t, ()), definitions[t])
                for t in types
            )
            total = reader.message_count
            # rosbags' end_time is just after the last message; an MCAP's end is that message's
            start, end = (reader.start_time, reader.end_time - 1) if total else (0, 0)
        return BagSummary(
            str(self.path), self.storage, tuple(str(f) for f in self.files), self._size(),
            start, end, total, topics, self._metadata.ros_distro if self._metadata else "",
        )  # fmt: skip

    @contextlib.contextmanager
    def _rosbags_reader(self) -> Iterator[Any]:
        if self.storage is Storage.ROS1:
            module = require("rosbags.rosbag1", "reading ROS 1 bags")
            reader = module.Reader(self.path)
        else:
            module = require("rosbags.rosbag2", "reading SQLite 3 bags")
            reader = module.Reader(self.path)
        try:
            reader.open()
        except Exception as exc:  # rosbags' ReaderError and what its parsers let through
            hint = "; `rosbag reindex` it" if "index" in str(exc).lower() else ""
            raise BagFormatError(str(self.path), f"cannot be read: {exc}{hint}") from None
        try:
            yield reader
        finally:
            reader.close()

    def messages(self, topics: Collection[str] | None = None) -> Iterator[BagMessage]:
        """The messages (of ``topics``, if given) in recorded order. Damage met on the way is
        appended to :attr:`damage` and reading goes on where it can."""
        wanted = None if topics is None else set(topics)
        if self.storage is Storage.MCAP:
            for file in self.files:
                if file.exists():
                    for message in scan_mcap(file, self.damage):
                        if wanted is None or message.topic in wanted:
                            yield message
            return
        with self._rosbags_reader() as reader:
            connections = [c for c in reader.connections if wanted is None or c.topic in wanted]
            if not connections:  # rosbags reads every connection when given none
                return
            for conn, stamp, data in reader.messages(connections=connections):
                yield BagMessage(conn.topic, conn.msgtype, bytes(data), stamp, stamp)


def open_bag(path: str | Path) -> Bag:
    """Open the bag at ``path`` (a rosbag2 folder, a ``.mcap`` or a ROS 1 ``.bag`` file)."""
    return Bag(path)
