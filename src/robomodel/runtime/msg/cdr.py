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
from collections.abc import Callable
from typing import Any, TypeVar

from robomodel.runtime.msg._cdr_decode import message_decoder as _message_decoder
from robomodel.runtime.msg._cdr_encode import message_encoder as _message_encoder
from robomodel.runtime.msg._cdr_strings import CDRError
from robomodel.runtime.msg.schema import Message

__all__ = [
    "CDRError",
    "deserialize",
    "payload_decoder",
    "payload_encoder",
    "prepare",
    "serialize",
]

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
    return payload_encoder(type(msg))(msg)


def deserialize(payload: bytes | bytearray | memoryview, cls: type[_M]) -> _M:
    """Decode a ROS 2 CDR payload into a ``cls`` message; CDRError if it does not fit."""
    return payload_decoder(cls)(bytes(payload))


def payload_encoder(cls: type[_M]) -> Callable[[_M], bytes]:
    """:func:`serialize` for messages of ``cls`` alone: a publisher keeps it, and saves the
    look-up of the type's code on every message."""
    coder = _payload_encoders.get(cls)
    if coder is None:
        coder = _payload_encoders[cls] = _make_payload_encoder(cls)
    return coder


def payload_decoder(cls: type[_M]) -> Callable[[bytes], _M]:
    """:func:`deserialize` of a ``bytes`` payload into ``cls``: a subscription keeps it."""
    coder = _payload_decoders.get(cls)
    if coder is None:
        coder = _payload_decoders[cls] = _make_payload_decoder(cls)
    return coder


_payload_encoders: dict[type[Message], Callable[[Any], bytes]] = {}
_payload_decoders: dict[type[Message], Callable[[bytes], Any]] = {}


def _make_payload_encoder(cls: type[Message]) -> Callable[[Message], bytes]:
    encode = _message_encoder(cls)

    def encode_payload(msg: Message) -> bytes:
        buf = bytearray(HEADER_LE)
        try:
            encode(buf, msg)
        except (struct.error, ValueError, TypeError, OverflowError) as exc:  # uint8[]: ValueError
            raise CDRError(f"{cls.__typename__}: a value does not fit its field: {exc}") from None
        return bytes(buf)

    return encode_payload


def _make_payload_decoder(cls: type[_M]) -> Callable[[bytes], _M]:
    decode = _message_decoder(cls)
    empty = not cls.__fields__  # its one placeholder byte carries nothing (absent: accepted)

    def decode_payload(data: bytes) -> _M:
        if data[:2] != b"\x00\x01" or len(data) < 4:
            _refuse_header(data)
        if empty:
            return cls()
        try:
            msg, _ = decode(data, 4)
        except struct.error as exc:
            raise CDRError(f"malformed {cls.__typename__} payload: {exc}") from None
        except UnicodeDecodeError:  # the generated code decodes strings inline
            raise CDRError("string is not valid UTF-8") from None
        return msg  # type: ignore[no-any-return]

    return decode_payload


def _refuse_header(data: bytes) -> None:
    if len(data) < 4:
        raise CDRError(f"payload of {len(data)} bytes has no CDR encapsulation header")
    raise CDRError(
        f"unsupported CDR encapsulation 0x{data[:2].hex()}; expected 0x0001 (CDR little endian)"
    )
