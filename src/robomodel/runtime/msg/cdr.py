"""ROS 2 CDR serialization: XCDR1 (plain CDR), little endian, with the encapsulation header.

Layout rules (OMG CDR as Fast-CDR implements them for ROS 2): every primitive is aligned to its
size (up to 8) relative to the first byte after the 4-byte header ``00 01 00 00``; strings are a
uint32 length including the terminating NUL, the bytes and the NUL; sequences a uint32 count
followed by the elements; fixed arrays just the elements; nested messages inline.
"""

from __future__ import annotations

import struct
from collections.abc import Callable
from typing import Any, TypeVar

from robomodel.runtime.msg._schema import PRIMITIVES, Array, Message, MessageTypeError, Seq, Spec

__all__ = ["CDRError", "deserialize", "serialize"]

HEADER_LE = b"\x00\x01\x00\x00"
_M = TypeVar("_M", bound=Message)

_Encoder = Callable[[bytearray, Any], None]
_Decoder = Callable[[memoryview, int], tuple[Any, int]]
_encoders: dict[type[Message], _Encoder] = {}
_decoders: dict[type[Message], _Decoder] = {}
_U32 = struct.Struct("<I")


class CDRError(MessageTypeError):
    """A payload that is not a valid CDR encoding of the expected type."""


def _pad(buf: bytearray, align: int) -> None:
    # Offsets are relative to the byte after the 4-byte encapsulation header.
    rem = (len(buf) - 4) % align
    if rem:
        buf.extend(b"\x00" * (align - rem))


def _align(offset: int, align: int) -> int:
    rem = (offset - 4) % align
    return offset + (align - rem) if rem else offset


def _encode_string(buf: bytearray, value: str) -> None:
    data = value.encode("utf-8")
    _pad(buf, 4)
    buf.extend(_U32.pack(len(data) + 1))
    buf.extend(data)
    buf.append(0)


def _primitive_encoder(name: str) -> _Encoder:
    if name == "string":
        return _encode_string
    code, size, _ = PRIMITIVES[name]
    packer = struct.Struct("<" + code)

    def encode(buf: bytearray, value: Any) -> None:
        _pad(buf, size)
        try:
            buf.extend(packer.pack(value))
        except struct.error as exc:
            raise CDRError(f"value {value!r} does not fit {name}: {exc}") from None

    return encode


def _encoder(spec: Spec) -> _Encoder:
    if isinstance(spec, str):
        return _primitive_encoder(spec)
    if isinstance(spec, (Seq, Array)):
        item = spec.item
        fixed = spec.size if isinstance(spec, Array) else None
        if isinstance(item, str) and item != "string":
            code, size, _ = PRIMITIVES[item]

            def encode_block(buf: bytearray, values: Any) -> None:
                values = list(values)
                if fixed is None:
                    _pad(buf, 4)
                    buf.extend(_U32.pack(len(values)))
                elif len(values) != fixed:
                    raise CDRError(f"fixed array needs {fixed} values, got {len(values)}")
                if values:
                    _pad(buf, size)
                    try:
                        buf.extend(struct.pack(f"<{len(values)}{code}", *values))
                    except struct.error as exc:
                        raise CDRError(f"values do not fit {item}[]: {exc}") from None

            return encode_block
        element = _encoder(item)

        def encode_seq(buf: bytearray, values: Any) -> None:
            values = list(values)
            if fixed is None:
                _pad(buf, 4)
                buf.extend(_U32.pack(len(values)))
            elif len(values) != fixed:
                raise CDRError(f"fixed array needs {fixed} values, got {len(values)}")
            for value in values:
                element(buf, value)

        return encode_seq
    return _message_encoder(spec)


def _message_encoder(cls: type[Message]) -> _Encoder:
    cached = _encoders.get(cls)
    if cached is not None:
        return cached
    fields = [(name, _encoder(spec)) for name, spec in cls.__fields__]

    def encode(buf: bytearray, msg: Any) -> None:
        for name, enc in fields:
            enc(buf, getattr(msg, name))

    _encoders[cls] = encode
    return encode


def _need(data: memoryview, offset: int, count: int) -> None:
    if offset + count > len(data):
        raise CDRError(
            f"payload truncated: need {count} bytes at offset {offset}, have {len(data) - offset}"
        )


def _decode_string(data: memoryview, offset: int) -> tuple[str, int]:
    offset = _align(offset, 4)
    _need(data, offset, 4)
    (length,) = _U32.unpack_from(data, offset)
    offset += 4
    _need(data, offset, length)
    if length == 0:
        return "", offset
    raw = bytes(data[offset : offset + length - 1])
    try:
        return raw.decode("utf-8"), offset + length
    except UnicodeDecodeError:
        raise CDRError("string is not valid UTF-8") from None


def _decoder(spec: Spec) -> _Decoder:
    if isinstance(spec, str):
        if spec == "string":
            return _decode_string
        code, size, _ = PRIMITIVES[spec]
        unpacker = struct.Struct("<" + code)

        def decode(data: memoryview, offset: int) -> tuple[Any, int]:
            offset = _align(offset, size)
            _need(data, offset, size)
            return unpacker.unpack_from(data, offset)[0], offset + size

        return decode
    if isinstance(spec, (Seq, Array)):
        item = spec.item
        fixed = spec.size if isinstance(spec, Array) else None

        def count_at(data: memoryview, offset: int) -> tuple[int, int]:
            if fixed is not None:
                return fixed, offset
            offset = _align(offset, 4)
            _need(data, offset, 4)
            return _U32.unpack_from(data, offset)[0], offset + 4

        if isinstance(item, str) and item != "string":
            code, size, _ = PRIMITIVES[item]

            def decode_block(data: memoryview, offset: int) -> tuple[Any, int]:
                count, offset = count_at(data, offset)
                if count == 0:
                    return [], offset
                offset = _align(offset, size)
                _need(data, offset, count * size)
                values = list(struct.unpack_from(f"<{count}{code}", data, offset))
                return values, offset + count * size

            return decode_block
        element = _decoder(item)

        def decode_seq(data: memoryview, offset: int) -> tuple[Any, int]:
            count, offset = count_at(data, offset)
            if count > len(data):
                raise CDRError(f"sequence length {count} exceeds the payload size")
            values = []
            for _ in range(count):
                value, offset = element(data, offset)
                values.append(value)
            return values, offset

        return decode_seq
    return _message_decoder(spec)


def _message_decoder(cls: type[Message]) -> _Decoder:
    cached = _decoders.get(cls)
    if cached is not None:
        return cached
    fields = [(name, _decoder(spec)) for name, spec in cls.__fields__]

    def decode(data: memoryview, offset: int) -> tuple[Any, int]:
        values = {}
        for name, dec in fields:
            values[name], offset = dec(data, offset)
        return cls(**values), offset

    _decoders[cls] = decode
    return decode


def serialize(msg: Message) -> bytes:
    """Encode ``msg`` as a ROS 2 CDR payload (what rmw puts on the wire)."""
    buf = bytearray(HEADER_LE)
    _message_encoder(type(msg))(buf, msg)
    return bytes(buf)


def deserialize(payload: bytes | bytearray | memoryview, cls: type[_M]) -> _M:
    """Decode a ROS 2 CDR payload into a ``cls`` message; CDRError if it does not fit."""
    data = memoryview(payload)
    if len(data) < 4:
        raise CDRError(f"payload of {len(data)} bytes has no CDR encapsulation header")
    if bytes(data[:2]) != b"\x00\x01":
        kind = bytes(data[:2]).hex()
        raise CDRError(
            f"unsupported CDR encapsulation 0x{kind}; expected 0x0001 (CDR little endian)"
        )
    msg, _ = _message_decoder(cls)(data, 4)
    return msg  # type: ignore[no-any-return]
