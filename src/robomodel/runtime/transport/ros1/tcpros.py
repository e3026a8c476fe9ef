"""TCPROS framing: connection headers and length-prefixed frames, read within bounds.

A connection header is a little-endian uint32 byte count followed by fields, each a uint32 byte
count and ``key=value`` (roscpp's ``Header::parse``). Messages follow as a uint32 byte count and
the serialized message; a service response is preceded by one ok byte (1: the response, 0: an
error string). Everything read from a peer is bounded: a header larger than
``MAX_HEADER_BYTES``, a frame larger than ``MAX_FRAME_BYTES`` or a field without ``=`` ends the
connection with a :class:`TcprosError` that says which, before anything is allocated.
"""

from __future__ import annotations

import socket
import struct
from collections.abc import Mapping

from robomodel.errors import RobomodelError

__all__ = [
    "MAX_FRAME_BYTES",
    "MAX_HEADER_BYTES",
    "TcprosError",
    "encode_header",
    "parse_header",
    "read_frame",
    "read_header",
    "recv_exact",
    "write_frame",
    "write_header",
]

MAX_HEADER_BYTES = 1 << 20  # a message_definition is a few kB; 1 MiB is generous
MAX_FRAME_BYTES = 256 << 20  # a 4K RGB image is 25 MB
_U32 = struct.Struct("<I")


class TcprosError(RobomodelError):
    """A TCPROS peer that sent something malformed or too large, or closed the connection."""


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


def recv_exact(sock: socket.socket, size: int) -> bytes:
    """``size`` bytes from ``sock``; TcprosError if the peer closes first."""
    chunks = bytearray()
    while len(chunks) < size:
        chunk = sock.recv(min(size - len(chunks), 1 << 20))
        if not chunk:
            raise TcprosError("connection closed by the peer")
        chunks += chunk
    return bytes(chunks)


def _read_size(sock: socket.socket, limit: int, what: str) -> int:
    (size,) = _U32.unpack(recv_exact(sock, 4))
    if size > limit:
        raise TcprosError(f"{what} of {size} bytes is larger than the {limit}-byte limit")
    return int(size)


def read_header(sock: socket.socket) -> dict[str, str]:
    return parse_header(recv_exact(sock, _read_size(sock, MAX_HEADER_BYTES, "connection header")))


def write_header(sock: socket.socket, fields: Mapping[str, str]) -> None:
    sock.sendall(encode_header(fields))


def read_frame(sock: socket.socket, limit: int = MAX_FRAME_BYTES) -> bytes:
    return recv_exact(sock, _read_size(sock, limit, "message"))


def write_frame(sock: socket.socket, payload: bytes) -> None:
    sock.sendall(_U32.pack(len(payload)) + payload)
