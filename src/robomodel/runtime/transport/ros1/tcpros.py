"""TCPROS framing: connection headers and length-prefixed frames, read within bounds.

A connection header is a little-endian uint32 byte count followed by fields, each a uint32 byte
count and ``key=value`` (roscpp's ``Header::parse``). Messages follow as a uint32 byte count and
the serialized message; a service response is preceded by one ok byte (1: the response, 0: an
error string). Everything read from a peer is bounded: a header larger than
``MAX_HEADER_BYTES``, a frame larger than ``MAX_FRAME_BYTES`` (or than the one size a
fixed-size message type has) or a field without ``=`` ends the connection with a
:class:`TcprosError` that says which, before anything is allocated.

All the frames a process is reading at once share ``FRAME_BUDGET_BYTES``: a frame is charged
twice its size (the bytes received, and the copy a message is decoded from) from its length
prefix until it is decoded, and a frame that does not fit is refused with
:class:`FrameRefused` (the connection is closed) instead of waiting, so no set of peers can
make a process hold more. A frame must arrive whole within ``FRAME_STALL_S`` plus its size at
``FRAME_MIN_RATE_BPS``, or its connection is dropped (so a slow peer cannot hold the budget).

A connection refused with an error header (:func:`refuse`) is closed by lingering
(:mod:`.linger`): a peer that sent frames after its header reads the error, not a reset.
"""

from __future__ import annotations

import contextlib
import socket
import struct
import time
from collections.abc import Iterator, Mapping

from robomodel.errors import RobomodelError
from robomodel.runtime.transport.ros1.budget import ByteBudget
from robomodel.runtime.transport.ros1.linger import close_after_answer

__all__ = [
    "FRAME_BUDGET_BYTES",
    "MAX_FRAME_BYTES",
    "MAX_HEADER_BYTES",
    "FrameRefused",
    "TcprosError",
    "encode_header",
    "frame_budget_in_use",
    "parse_header",
    "read_frame",
    "read_header",
    "receive_frame",
    "recv_exact",
    "refuse",
    "write_frame",
    "write_header",
]

MAX_HEADER_BYTES = 1 << 20  # a message_definition is a few kB; 1 MiB is generous
MAX_FRAME_BYTES = 256 << 20  # a 4K RGB image is 25 MB
FRAME_BUDGET_BYTES = 512 << 20  # one frame of the largest size, charged twice, at a time
FRAME_STALL_S = 30.0  # a frame must be in within this, plus its size at FRAME_MIN_RATE_BPS
FRAME_MIN_RATE_BPS = 1 << 20  # a peer slower than 1 MiB/s cannot hold the budget for long
_U32 = struct.Struct("<I")


class TcprosError(RobomodelError):
    """A TCPROS peer that sent something malformed or too large, or closed the connection."""


class FrameRefused(TcprosError):
    """A frame over its size limit, or over what the frame budget has left."""


_BUDGET = ByteBudget(FRAME_BUDGET_BYTES)


def frame_budget_in_use() -> int:
    """Bytes of the frame budget charged right now (0 when no frame is being read)."""
    return _BUDGET.used


def encode_header(fields: Mapping[str, str]) -> bytes:
    body = bytearray()
    for key, value in fields.items():
        field = f"{key}={value}".encode()
        body += _U32.pack(len(field)) + field
    return _U32.pack(len(body)) + bytes(body)


def parse_header(body: bytes) -> dict[str, str]:
    """The fields of a header body (without its leading byte count)."""
    fields: dict[str, str] = {}
    offset = 0
    while offset < len(body):
        if offset + 4 > len(body):
            raise TcprosError("connection header: a field's length is cut off")
        (size,) = _U32.unpack_from(body, offset)
        offset += 4
        if size > len(body) - offset:
            raise TcprosError(f"connection header: a field of {size} bytes overruns the header")
        field = body[offset : offset + size]
        offset += size
        key, sep, value = field.partition(b"=")
        if not sep:
            raise TcprosError(f"connection header: field {field[:40]!r} has no '='")
        try:
            fields[key.decode()] = value.decode()
        except UnicodeDecodeError:
            raise TcprosError("connection header: a field is not UTF-8") from None
    return fields


def recv_exact(sock: socket.socket, size: int, *, within_s: float | None = None) -> bytes:
    """``size`` bytes from ``sock``; TcprosError if the peer closes first, TimeoutError if
    they are not all in within ``within_s`` (or the socket's own timeout for one piece)."""
    deadline = None if within_s is None else time.monotonic() + within_s
    piece_s = sock.gettimeout()
    chunks = bytearray()
    while len(chunks) < size:
        if deadline is not None:
            left_s = deadline - time.monotonic()
            if left_s <= 0:
                raise TimeoutError(f"{len(chunks)} of {size} bytes in {within_s:.0f} s")
            sock.settimeout(left_s if piece_s is None else min(left_s, piece_s))
        chunk = sock.recv(min(size - len(chunks), 1 << 20))
        if not chunk:
            raise TcprosError("connection closed by the peer")
        chunks += chunk
    return bytes(chunks)


def _read_size(sock: socket.socket, limit: int, what: str) -> int:
    (size,) = _U32.unpack(recv_exact(sock, 4))
    if size > limit:
        raise FrameRefused(f"{what} of {size} bytes is larger than the {limit}-byte limit")
    return int(size)


def read_header(sock: socket.socket) -> dict[str, str]:
    return parse_header(recv_exact(sock, _read_size(sock, MAX_HEADER_BYTES, "connection header")))


def write_header(sock: socket.socket, fields: Mapping[str, str]) -> None:
    sock.sendall(encode_header(fields))


def refuse(sock: socket.socket, reason: str) -> None:
    """Answer a connection with an ``error`` header (rospy's and roscpp's refusal) and close it
    without a reset, whatever the peer sent after its header; ``sock`` is the caller's no
    longer."""
    with contextlib.suppress(OSError):
        write_header(sock, {"error": reason})
    close_after_answer(sock)


@contextlib.contextmanager
def receive_frame(sock: socket.socket, limit: int = MAX_FRAME_BYTES) -> Iterator[bytes]:
    """The next frame's payload, charged to the frame budget until the block ends (decode it
    inside). FrameRefused if it is larger than ``limit`` or the budget has no room for it."""
    size = _read_size(sock, min(limit, MAX_FRAME_BYTES), "message")
    if not _BUDGET.take(2 * size):
        raise FrameRefused(
            f"a message of {size} bytes does not fit in what is left of the "
            f"{FRAME_BUDGET_BYTES >> 20} MiB budget of messages being read"
        )
    try:
        waiting = sock.gettimeout()
        try:
            data = recv_exact(sock, size, within_s=FRAME_STALL_S + size / FRAME_MIN_RATE_BPS)
        finally:
            sock.settimeout(waiting)
        yield data
    finally:
        _BUDGET.give(2 * size)


def read_frame(sock: socket.socket, limit: int = MAX_FRAME_BYTES) -> bytes:
    """The next frame's payload (within ``limit`` and the frame budget while it is read)."""
    with receive_frame(sock, limit) as data:
        return data


def write_frame(sock: socket.socket, payload: bytes) -> None:
    sock.sendall(_U32.pack(len(payload)) + payload)
