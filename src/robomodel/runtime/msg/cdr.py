"""ROS 2 CDR serialization: XCDR1 (plain CDR), little endian, with the encapsulation header.

Layout rules (OMG CDR as Fast-CDR implements them for ROS 2): every primitive is aligned to its
size (up to 8) relative to the first byte after the 4-byte header ``00 01 00 00``; strings are a
uint32 length including the terminating NUL, the bytes and the NUL; sequences a uint32 count
followed by the elements; fixed arrays just the elements; nested messages inline.

For speed, each message type gets an encoder and a decoder generated as Python source with
every field inlined, nested messages and the elements of message sequences included (no
per-field or per-message function calls), and consecutive fixed-size values packed or
unpacked by one ``struct`` call whose format holds the alignment padding wherever the offset
is known when the code is generated (a ``TransformStamped`` is two such calls and its two
strings).
"""

from __future__ import annotations

import struct
from typing import TypeVar

from robomodel.runtime.msg._cdr_decode import message_decoder as _message_decoder
from robomodel.runtime.msg._cdr_encode import message_encoder as _message_encoder
from robomodel.runtime.msg._cdr_strings import CDRError
from robomodel.runtime.msg._schema import Message

__all__ = ["CDRError", "deserialize", "prepare", "serialize"]

HEADER_LE = b"\x00\x01\x00\x00"
_M = TypeVar("_M", bound=Message)


def prepare(cls: type[Message]) -> None:
    """Generate ``cls``'s encoder and decoder now (each is generated once per type).

    A publisher or subscription calls this when it is created, so the first message does not
    pay for the code generation (a few ms for a nested type such as TFMessage: with messages
    arriving every millisecond, the first ones queued up behind it).
    """
    _message_encoder(cls)
    _message_decoder(cls)


def serialize(msg: Message) -> bytes:
    """Encode ``msg`` as a ROS 2 CDR payload (what rmw puts on the wire)."""
    buf = bytearray(HEADER_LE)
    try:
        _message_encoder(type(msg))(buf, msg)
    except (struct.error, ValueError, TypeError) as exc:  # bytes() of uint8[]: ValueError
        raise CDRError(f"{type(msg).__typename__}: a value does not fit its field: {exc}") from None
    return bytes(buf)


def deserialize(payload: bytes | bytearray | memoryview, cls: type[_M]) -> _M:
    """Decode a ROS 2 CDR payload into a ``cls`` message; CDRError if it does not fit."""
    data = bytes(payload)
    if len(data) < 4:
        raise CDRError(f"payload of {len(data)} bytes has no CDR encapsulation header")
    if data[:2] != b"\x00\x01":
        kind = data[:2].hex()
        raise CDRError(
            f"unsupported CDR encapsulation 0x{kind}; expected 0x0001 (CDR little endian)"
        )
    if not cls.__fields__:  # its one placeholder byte carries nothing (absent: accepted)
        return cls()
    try:
        msg, _ = _message_decoder(cls)(data, 4)
    except struct.error as exc:
        raise CDRError(f"malformed {cls.__typename__} payload: {exc}") from None
    except UnicodeDecodeError:  # the generated code decodes strings inline
        raise CDRError("string is not valid UTF-8") from None
    return msg  # type: ignore[no-any-return]
