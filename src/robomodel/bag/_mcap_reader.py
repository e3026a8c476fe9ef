"""Reading MCAP files record by record with the ``mcap`` library, keeping what is sound.

The file is read in order (``StreamReader`` with ``emit_chunks``), so a file without its
summary and footer (a recording killed mid-way) is read up to its last complete record, as
``mcap recover`` does. Before each record its header is checked against the file's size, so a
truncated record is reported with its offset instead of being half-read; each chunk's CRC is
checked, and a chunk that fails it is skipped (reported) while the following ones are read.

A chunk is decompressed only if the size it declares is at most ``MAX_CHUNK_BYTES`` and at most
``MAX_CHUNK_RATIO`` times the file's size, and into at most that many bytes (a stream that
expands further is damage, not a reason to allocate): a 66 KB "zip bomb" chunk declaring 2 GiB
is refused with one line instead of filling the memory.
"""

from __future__ import annotations

import dataclasses
import importlib
import os
import struct
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

from robomodel.bag._deps import require
from robomodel.bag.exceptions import BagFormatError
from robomodel.bag.model import BagMessage, Damage
from robomodel.errors import MissingDependencyError

__all__ = ["McapChannel", "scan_mcap"]

MAGIC = b"\x89MCAP0\r\n"
_HEADER = struct.Struct("<BQ")  # opcode, record length
_OPCODE_FOOTER = 0x02
_OPCODE_CHUNK = 0x06
MAX_CHUNK_BYTES = 256 << 20  # as a TCPROS frame; ROS 2 writers make chunks of about 1 MiB
MAX_CHUNK_RATIO = 1000  # zstd and lz4 reach a few hundred on camera images of one colour


@dataclasses.dataclass(frozen=True, slots=True)
class McapChannel:
    """A channel (topic) and the name, encoding and metadata of its schema."""

    topic: str
    type: str
    message_encoding: str
    metadata: dict[str, str]
    definition: str = ""  # the schema's text (ros2msg or ros1msg)


def _zstd_bounded(data: bytes, limit: int) -> bytes:
    """At most ``limit`` bytes of the zstd stream ``data``, with whichever zstd module is
    there (Python 3.14's, the backport rosbags depends on, or mcap's ``zstandard``)."""
    for name in ("compression.zstd", "backports.zstd"):
        try:
            zstd = importlib.import_module(name)
        except ImportError:
            continue
        return bytes(zstd.ZstdDecompressor().decompress(data, max_length=limit))
    try:
        zstandard = importlib.import_module("zstandard")
    except ImportError:
        raise MissingDependencyError(
            "zstandard", "bag", "reading zstd-compressed MCAP chunks"
        ) from None
    out = bytearray()
    with zstandard.ZstdDecompressor().stream_reader(data) as stream:
        while len(out) < limit and (piece := stream.read(min(limit - len(out), 1 << 20))):
            out += piece
    return bytes(out)


def _lz4_bounded(data: bytes, limit: int) -> bytes:
    """At most ``limit`` bytes of the lz4 frame ``data``."""
    frame = require("lz4.frame", "reading lz4-compressed MCAP chunks")
    return bytes(frame.LZ4FrameDecompressor().decompress(data, max_length=limit))


def _decompressed(chunk: Any, limit: int) -> bytes:
    """The chunk's records, decompressed into at most ``limit`` bytes."""
    if chunk.compression == "zstd":
        return _zstd_bounded(chunk.data, limit)
    if chunk.compression == "lz4":
        return _lz4_bounded(chunk.data, limit)
    return bytes(chunk.data[:limit])


class _Scan:
    def __init__(
        self,
        path: Path,
        damage: list[Damage],
        on_channel: Callable[[McapChannel], None] | None,
        file_size: int,
    ) -> None:
        self.path = path
        self.chunk_limit = min(MAX_CHUNK_BYTES, MAX_CHUNK_RATIO * file_size)
        self.damage = damage
        self.on_channel = on_channel
        self.schemas: dict[int, Any] = {}
        self.channels: dict[int, McapChannel] = {}
        self._records = require("mcap.records", "reading MCAP bags")
        self._stream_reader = require("mcap.stream_reader", "reading MCAP bags")

    def note(self, offset: int | None, reason: str) -> None:
        self.damage.append(Damage(str(self.path), offset, reason))

    def _add_channel(self, raw: Any) -> None:
        if raw.id in self.channels:  # repeated in the summary, or in every split file
            return
        schema = self.schemas.get(raw.schema_id)
        text = bytes(schema.data).decode("utf-8", "replace") if schema else ""
        channel = McapChannel(
            raw.topic, schema.name if schema else "", raw.message_encoding, dict(raw.metadata), text
        )
        self.channels[raw.id] = channel
        if self.on_channel is not None:
            self.on_channel(channel)

    def records(self, record: Any, offset: int) -> Iterator[Any]:
        """The records inside ``record`` (a chunk's, CRC-checked), or ``record`` itself."""
        if not isinstance(record, self._records.Chunk):
            yield record
            return
        declared = int(record.uncompressed_size)
        if declared > self.chunk_limit:
            raise BagFormatError(
                str(self.path),
                f"a chunk declares {declared} bytes uncompressed; at most {self.chunk_limit} "
                f"are read ({MAX_CHUNK_BYTES >> 20} MiB, and {MAX_CHUNK_RATIO} times the "
                "file's size): a decompression bomb or a damaged file",
                offset=offset,
            )
        try:
            plain = _decompressed(record, declared + 1)
        except MissingDependencyError:
            raise
        except Exception as exc:  # the codecs' errors (ZstdError, lz4's RuntimeError) share none
            self.note(offset, f"chunk does not decompress ({exc}); its messages are skipped")
            return
        if len(plain) != declared:
            got = "beyond" if len(plain) > declared else f"to only {len(plain)} of"
            self.note(offset, f"chunk expands {got} the {declared} bytes it declares; its "
                              "messages are skipped")  # fmt: skip
            return
        record = dataclasses.replace(record, compression="", data=plain)
        try:
            inner = self._stream_reader.breakup_chunk(record, validate_crc=True)
        except self._stream_reader.CRCValidationError as exc:
            self.note(offset, f"chunk fails its CRC ({exc}); its messages are skipped")
            return
        except (ValueError, struct.error, KeyError) as exc:
            self.note(offset, f"chunk cannot be decoded ({exc}); its messages are skipped")
            return
        yield from inner

    def message(self, record: Any) -> BagMessage | None:
        records = self._records
        if isinstance(record, records.Schema):
            self.schemas[record.id] = record
        elif isinstance(record, records.Channel):
            self._add_channel(record)
        elif isinstance(record, records.Message):
            channel = self.channels.get(record.channel_id)
            if channel is not None:
                return BagMessage(
                    channel.topic, channel.type, record.data, record.log_time, record.publish_time
                )
        return None


def _check_next(fd: int, offset: int, size: int) -> str | None:
    """Why the record at ``offset`` cannot be read whole, or None if it can."""
    remaining = size - offset
    if remaining == 0:
        return "file ends without the MCAP footer (the recording was not closed)"
    if remaining < _HEADER.size:
        return f"truncated record header ({remaining} of {_HEADER.size} bytes)"
    opcode, length = _HEADER.unpack(os.pread(fd, _HEADER.size, offset))
    if length > remaining - _HEADER.size:
        kind = "chunk" if opcode == _OPCODE_CHUNK else f"record (opcode 0x{opcode:02x})"
        return f"truncated {kind}: {length} bytes declared, {remaining - _HEADER.size} present"
    return None


def scan_mcap(
    path: Path, damage: list[Damage], on_channel: Callable[[McapChannel], None] | None = None
) -> Iterator[BagMessage]:
    """Every readable message of ``path`` in file order; problems are appended to ``damage``.

    BagFormatError when ``path`` is not an MCAP file at all."""
    with path.open("rb") as handle:
        head = handle.read(len(MAGIC))
        if head != MAGIC:
            raise BagFormatError(str(path), "not an MCAP file (bad magic)", offset=0)
        handle.seek(0)
        size = os.fstat(handle.fileno()).st_size
        scan = _Scan(path, damage, on_channel, size)
        reader = scan._stream_reader.StreamReader(handle, emit_chunks=True)
        records = reader.records
        offset = len(MAGIC)
        while True:
            if offset > len(MAGIC):  # the first call reads the magic, then the header record
                problem = _check_next(handle.fileno(), offset, size)
                if problem is not None:
                    scan.note(offset, problem)
                    return
            try:
                record = next(records)
            except StopIteration:
                return
            except Exception as exc:  # the library's parse errors have no common base
                scan.note(offset, f"unreadable record ({type(exc).__name__}: {exc})")
                return
            for inner in scan.records(record, offset):
                message = scan.message(inner)
                if message is not None:
                    yield message
            if isinstance(record, scan._records.Footer):
                return
            offset = handle.tell()
