"""rosbag2 folders with MCAP files, written with Foxglove's ``mcap`` library.

Layout as rosbag2_storage_mcap writes it: profile ``ros2``, one schema per type (encoding
``ros2msg``), one channel per topic (message encoding ``cdr``, ``offered_qos_profiles`` and
``topic_type_hash`` in its metadata), messages with ``log_time`` = receive time and
``publish_time`` = the publisher's send time (rosbag2 Jazzy's ``recv_timestamp`` and
``send_timestamp``), uncompressed chunks with CRCs, and a summary with indexes at the end.

Crash safety: the chunk in progress is closed and the file flushed at least every
``flush_period_s`` (and whenever ``chunk_size`` is reached), and ``metadata.yaml`` is
rewritten (atomically) at each flush. A recording killed with SIGKILL keeps every chunk
flushed before the kill; it lacks the summary and footer (readers scan it, as ``mcap
recover`` does) and loses the messages of the last ``flush_period_s`` at most.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import IO, Any

import yaml

from robomodel._version import __version__
from robomodel.bag._deps import require
from robomodel.bag._metadata import FileEntry, _qos_dict, write_metadata
from robomodel.bag._writer_base import NO_SPLIT, BagWriter, SplitPolicy
from robomodel.bag.exceptions import BagWriteError
from robomodel.bag.model import Storage, TopicSummary
from robomodel.bag.typedefs import rihs01, ros2msg_definition
from robomodel.runtime.msg import Message
from robomodel.runtime.qos import QoSProfile

__all__ = ["McapFolderWriter"]

CHUNK_SIZE = 768 * 1024  # rosbag2_storage_mcap's default chunk size
# A message's bytes in the file besides its data: the Message record (opcode, length, channel,
# sequence, log and publish time: 31 bytes) and its entry in the chunk's MessageIndex (16).
MESSAGE_OVERHEAD = 47


@dataclass
class _Topic:
    msg_type: type[Message]
    offered_qos: tuple[QoSProfile, ...]
    count: int = 0


@dataclass
class _File:
    path: Path
    stream: IO[bytes]
    writer: Any
    channels: dict[str, int] = field(default_factory=dict)
    schemas: dict[str, int] = field(default_factory=dict)
    first_ns: int | None = None
    last_ns: int = 0
    count: int = 0
    written: int = 0  # the stream's position when last looked at
    pending: int = 0  # bytes of messages in the chunk the mcap writer still holds in memory

    @property
    def size_bytes(self) -> int:
        """The file's size once the chunk in progress is written (as far as it is known)."""
        if self.stream.closed:
            return self.path.stat().st_size
        return self.stream.tell() + self.pending

    def added(self, data_bytes: int) -> None:
        """Account for a message just given to the mcap writer, which writes its chunk out
        (and the stream's position moves) once the chunk is full."""
        position = self.stream.tell()
        if position != self.written:
            self.written, self.pending = position, 0
        else:
            self.pending += data_bytes + MESSAGE_OVERHEAD

    def entry(self) -> FileEntry:
        return FileEntry(self.path.name, self.first_ns or 0, self.last_ns, self.count)


class McapFolderWriter(BagWriter):
    """Writes the rosbag2 folder ``folder`` (which must not exist yet)."""

    def __init__(
        self,
        folder: Path,
        *,
        split: SplitPolicy = NO_SPLIT,
        chunk_size: int = CHUNK_SIZE,
        flush_period_s: float = 1.0,
    ) -> None:
        self._mcap = require("mcap.writer", "writing MCAP bags")
        if folder.exists():
            raise BagWriteError(str(folder), "exists already; give another output with -o")
        folder.mkdir(parents=True)
        self.folder = folder
        self._split = split
        self._chunk_size = chunk_size
        self._flush_period_s = flush_period_s
        self._topics: dict[str, _Topic] = {}
        self._closed_files: list[FileEntry] = []
        self._closed_bytes = 0
        self._last_flush = time.monotonic()
        self.message_count = 0
        self._file = self._open(0)
        self._write_metadata()

    def _open(self, index: int) -> _File:
        path = self.folder / f"{self.folder.name}_{index}.mcap"
        stream = path.open("xb")
        writer = self._mcap.Writer(
            stream, chunk_size=self._chunk_size, compression=self._mcap.CompressionType.NONE
        )
        writer.start(profile="ros2", library=f"robomodel-{__version__}")
        stream.flush()
        return _File(path, stream, writer, written=stream.tell())

    def add_topic(
        self, topic: str, msg_type: type[Message], offered_qos: tuple[QoSProfile, ...]
    ) -> None:
        if topic not in self._topics:
            self._topics[topic] = _Topic(msg_type, offered_qos)
            self._channel(topic)  # listed (with 0 messages) even if nothing comes

    def _channel(self, topic: str) -> int:
        file = self._file
        channel = file.channels.get(topic)
        if channel is not None:
            return channel
        entry = self._topics[topic]
        typename = entry.msg_type.__typename__
        schema = file.schemas.get(typename)
        if schema is None:
            data = ros2msg_definition(entry.msg_type).encode()
            schema = file.writer.register_schema(typename, "ros2msg", data)
            file.schemas[typename] = schema
        qos_text = yaml.safe_dump([_qos_dict(q) for q in entry.offered_qos], sort_keys=False)
        metadata = {
            "offered_qos_profiles": qos_text,
            "topic_type_hash": rihs01(entry.msg_type),
        }
        channel = file.writer.register_channel(topic, "cdr", schema, metadata)
        file.channels[topic] = channel
        return int(channel)

    def write(
        self,
        topic: str,
        cdr: bytes,
        log_time_ns: int,
        publish_time_ns: int,
        sequence: int = 0,
    ) -> None:
        file = self._file
        if file.count and self._split.due(file.size_bytes, file.first_ns, log_time_ns):
            self._rotate()
            file = self._file
        file.writer.add_message(
            self._channel(topic), log_time_ns, cdr, publish_time_ns, sequence & 0xFFFFFFFF
        )
        file.added(len(cdr))
        if file.first_ns is None:
            file.first_ns = log_time_ns
        file.first_ns = min(file.first_ns, log_time_ns)
        file.last_ns = max(file.last_ns, log_time_ns)
        file.count += 1
        self._topics[topic].count += 1
        self.message_count += 1
        if time.monotonic() - self._last_flush >= self._flush_period_s:
            self.flush()

    def _rotate(self) -> None:
        self._finish(self._file)
        self._closed_files.append(self._file.entry())
        self._closed_bytes += self._file.path.stat().st_size
        self._file = self._open(len(self._closed_files))
        self._write_metadata()

    @staticmethod
    def _finish(file: _File) -> None:
        file.writer.finish()
        file.stream.close()

    def flush(self) -> None:
        """Close the chunk in progress, write it out and update metadata.yaml."""
        self._last_flush = time.monotonic()
        self._file.writer.flush()
        self._file.written, self._file.pending = self._file.stream.tell(), 0
        self._write_metadata()

    def close(self) -> None:
        self._finish(self._file)
        self._write_metadata()

    def _write_metadata(self) -> None:
        files = [*self._closed_files, self._file.entry()]
        topics = [
            (
                TopicSummary(name, t.msg_type.__typename__, t.count, "cdr", t.offered_qos),
                rihs01(t.msg_type),
            )
            for name, t in self._topics.items()
        ]
        write_metadata(self.folder, Storage.MCAP, files, topics)

    @property
    def size_bytes(self) -> int:
        return self._closed_bytes + self._file.size_bytes

    @property
    def files(self) -> tuple[str, ...]:
        return (*(str(self.folder / f.path) for f in self._closed_files), str(self._file.path))
