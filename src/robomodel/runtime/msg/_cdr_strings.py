"""CDR ``string[]`` coding for the generated codecs (:mod:`.cdr`, which codes a lone ``string``
inline), with a memo for the ``string[]`` that repeats from one message to the next.

A ``string[]`` is most often the same list message after message: a JointState's joint names
(32 for talos, half of its encode and decode time), a controller's joints. Each ``string[]``
field of a generated codec gets a :class:`StringsMemo`: the encoder keeps the last list it
encoded with its bytes, the decoder the last bytes it decoded with their strings, and a repeat
is one comparison (``tuple ==`` on the encode side, ``bytes.startswith`` at the offset on the
decode side) instead of a loop over the strings. What goes on the wire, and what a decoder
returns, is the same with or without the memo: CDR's padding of a string depends only on its
offset modulo 4, which is part of the memo's key, and a decoded list is a new list each time
(str values are immutable, so sharing them is safe). Only ``string[]`` of at most
``MEMO_MAX_BYTES`` (16 KiB) are remembered, so a memo holds at most twice that.
"""

from __future__ import annotations

import struct
from collections.abc import Sequence

from robomodel.runtime.msg.schema import MessageTypeError

__all__ = ["MEMO_MAX_BYTES", "CDRError", "StringsMemo", "decode_strings", "encode_strings"]

MEMO_MAX_BYTES = 16 * 1024
_UINT32 = struct.Struct("<I")
_PAD = (b"", b"\x00\x00\x00", b"\x00\x00", b"\x00")  # indexed by offset & 3


class CDRError(MessageTypeError):
    """A payload that is not a valid CDR encoding of the expected type."""


def encode_strings(buf: bytearray, values: Sequence[str]) -> None:
    """Append each of ``values`` as a CDR string (aligned uint32 length with the NUL, the
    bytes, the NUL), in one loop."""
    pack = _UINT32.pack
    for value in values:
        data = value.encode("utf-8")
        buf += _PAD[len(buf) & 3]
        buf += pack(len(data) + 1)
        buf += data
        buf.append(0)


def decode_strings(data: bytes, o: int, count: int) -> tuple[list[str], int]:
    """``count`` strings from ``o`` (a ``string[]``'s items): one loop with local names, not a
    call per string (a JointState's 32 names were half its decode time)."""
    out: list[str] = []
    append = out.append
    n = len(data)
    unpack = _UINT32.unpack_from
    try:
        for _ in range(count):
            o += (-(o - 4)) & 3
            if o + 4 > n:
                raise CDRError(f"payload truncated: string length at offset {o}")
            (length,) = unpack(data, o)
            o += 4
            end = o + length
            if end > n:
                raise CDRError(f"payload truncated: string of {length} bytes at offset {o}")
            append(data[o : end - 1].decode("utf-8") if length else "")
            o = end
    except UnicodeDecodeError:
        raise CDRError("string is not valid UTF-8") from None
    return out, o


class StringsMemo:
    """The last ``string[]`` one generated field encoded and the last one it decoded.

    Each slot is one tuple replaced whole, so threads that share a codec read either the old
    or the new entry, never half of one.
    """

    __slots__ = ("_decoded", "_encoded")

    def __init__(self) -> None:
        self._encoded: tuple[tuple[str, ...], int, bytes] | None = None
        self._decoded: tuple[int, int, bytes, tuple[str, ...]] | None = None

    def encode(self, buf: bytearray, values: Sequence[str]) -> None:
        """Append the count and the strings of ``values`` (the count already aligned)."""
        items = tuple(values)
        buf += _UINT32.pack(len(items))
        align = len(buf) & 3
        last = self._encoded
        if last is not None and last[1] == align and last[0] == items:
            buf += last[2]
            return
        start = len(buf)
        encode_strings(buf, items)
        if len(buf) - start <= MEMO_MAX_BYTES:
            self._encoded = (items, align, bytes(buf[start:]))

    def decode(self, data: bytes, o: int, count: int) -> tuple[list[str], int]:
        """The ``count`` strings at ``o`` and the offset after them."""
        last = self._decoded
        align = o & 3
        if last is not None and last[:2] == (align, count) and data.startswith(last[2], o):
            return list(last[3]), o + len(last[2])
        out, end = decode_strings(data, o, count)
        if end - o <= MEMO_MAX_BYTES:
            self._decoded = (align, count, data[o:end], tuple(out))
        return out, end
