"""ROS 2 CDR serialization: XCDR1 (plain CDR), little endian, with the encapsulation header.

Layout rules (OMG CDR as Fast-CDR implements them for ROS 2): every primitive is aligned to its
size (up to 8) relative to the first byte after the 4-byte header ``00 01 00 00``; strings are a
uint32 length including the terminating NUL, the bytes and the NUL; sequences a uint32 count
followed by the elements; fixed arrays just the elements; nested messages inline.

For speed, each message type gets an encoder and a decoder generated as Python source with
every field inlined (no per-field function calls); nested types and sequences of messages
call the nested type's generated function.
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
_Decoder = Callable[[bytes, int], tuple[Any, int]]
_encoders: dict[type[Message], _Encoder] = {}
_decoders: dict[type[Message], _Decoder] = {}


class CDRError(MessageTypeError):
    """A payload that is not a valid CDR encoding of the expected type."""


# -- runtime helpers used by the generated code ----------------------------------------------


def _encode_string(buf: bytearray, value: str) -> None:
    data = value.encode("utf-8")
    rem = (len(buf) - 4) & 3
    if rem:
        buf += b"\x00" * (4 - rem)
    buf += (len(data) + 1).to_bytes(4, "little")
    buf += data
    buf.append(0)


def _decode_string(data: bytes, o: int) -> tuple[str, int]:
    o += (-(o - 4)) & 3
    if o + 4 > len(data):
        raise CDRError(f"payload truncated: string length at offset {o}")
    length = int.from_bytes(data[o : o + 4], "little")
    o += 4
    if o + length > len(data):
        raise CDRError(f"payload truncated: string of {length} bytes at offset {o}")
    if length == 0:
        return "", o
    try:
        return data[o : o + length - 1].decode("utf-8"), o + length
    except UnicodeDecodeError:
        raise CDRError("string is not valid UTF-8") from None


def _count(data: bytes, o: int) -> tuple[int, int]:
    o += (-(o - 4)) & 3
    if o + 4 > len(data):
        raise CDRError(f"payload truncated: sequence length at offset {o}")
    n = int.from_bytes(data[o : o + 4], "little")
    if n > len(data):
        raise CDRError(f"sequence length {n} exceeds the payload size")
    return n, o + 4


def _fixed(values: Any, size: int) -> list[Any]:
    items: list[Any] = list(values)
    if len(items) != size:
        raise CDRError(f"fixed array needs {size} values, got {len(items)}")
    return items


# -- code generation -------------------------------------------------------------------------


class _Gen:
    """Accumulates generated source lines and the names they refer to."""

    def __init__(self) -> None:
        self.lines: list[str] = []
        self.env: dict[str, Any] = {
            "struct": struct,
            "CDRError": CDRError,
            "_encode_string": _encode_string,
            "_decode_string": _decode_string,
            "_count": _count,
            "_fixed": _fixed,
        }
        self._n = 0

    def name(self, prefix: str) -> str:
        self._n += 1
        return f"{prefix}{self._n}"

    def ref(self, obj: Any, prefix: str) -> str:
        name = self.name(prefix)
        self.env[name] = obj
        return name

    def emit(self, depth: int, line: str) -> None:
        self.lines.append("    " * depth + line)


def _enc_pad(g: _Gen, d: int, align: int) -> None:
    if align > 1:
        g.emit(d, f"r = (len(buf) - 4) & {align - 1}")
        g.emit(d, f"if r: buf += b'\\x00' * ({align} - r)")


def _enc_field(g: _Gen, d: int, spec: Spec, expr: str) -> None:
    if isinstance(spec, str):
        if spec == "string":
            g.emit(d, f"_encode_string(buf, {expr})")
            return
        code, size, _ = PRIMITIVES[spec]
        packer = g.ref(struct.Struct("<" + code).pack, "pk")
        _enc_pad(g, d, size)
        g.emit(d, f"buf += {packer}({expr})")
        return
    if isinstance(spec, (Seq, Array)):
        item = spec.item
        seq = g.name("s")
        if isinstance(spec, Array):
            g.emit(d, f"{seq} = _fixed({expr}, {spec.size})")
        else:
            g.emit(d, f"{seq} = {expr}")
            _enc_pad(g, d, 4)
            g.emit(d, f"buf += len({seq}).to_bytes(4, 'little')")
        if isinstance(item, str) and item != "string":
            code, size, _ = PRIMITIVES[item]
            g.emit(d, f"if {seq}:")
            _enc_pad(g, d + 1, size)
            g.emit(d + 1, f"buf += struct.pack('<%d{code}' % len({seq}), *{seq})")
            return
        var = g.name("v")
        g.emit(d, f"for {var} in {seq}:")
        _enc_field(g, d + 1, item, var)
        return
    g.emit(d, f"{g.ref(_message_encoder(spec), 'enc')}(buf, {expr})")


def _dec_field(g: _Gen, d: int, spec: Spec, target: str) -> None:
    if isinstance(spec, str):
        if spec == "string":
            g.emit(d, f"{target}, o = _decode_string(data, o)")
            return
        code, size, _ = PRIMITIVES[spec]
        unpacker = g.ref(struct.Struct("<" + code).unpack_from, "up")
        if size > 1:
            g.emit(d, f"o += (-(o - 4)) & {size - 1}")
        g.emit(d, f"if o + {size} > n: raise CDRError(f'payload truncated at offset {{o}}')")
        g.emit(d, f"{target}, = {unpacker}(data, o)")
        g.emit(d, f"o += {size}")
        return
    if isinstance(spec, (Seq, Array)):
        item = spec.item
        count = g.name("c")
        if isinstance(spec, Array):
            g.emit(d, f"{count} = {spec.size}")
        else:
            g.emit(d, f"{count}, o = _count(data, o)")
        if isinstance(item, str) and item != "string":
            code, size, _ = PRIMITIVES[item]
            g.emit(d, f"if {count}:")
            if size > 1:
                g.emit(d + 1, f"o += (-(o - 4)) & {size - 1}")
            g.emit(
                d + 1,
                f"if o + {count} * {size} > n: raise CDRError(f'payload truncated at offset {{o}}')",
            )
            g.emit(d + 1, f"{target} = list(struct.unpack_from('<%d{code}' % {count}, data, o))")
            g.emit(d + 1, f"o += {count} * {size}")
            g.emit(d, "else:")
            g.emit(d + 1, f"{target} = []")
            return
        items, var = g.name("l"), g.name("v")
        g.emit(d, f"{items} = []")
        g.emit(d, f"for _ in range({count}):")
        _dec_field(g, d + 1, item, var)
        g.emit(d + 1, f"{items}.append({var})")
        g.emit(d, f"{target} = {items}")
        return
    g.emit(d, f"{target}, o = {g.ref(_message_decoder(spec), 'dec')}(data, o)")


def _message_encoder(cls: type[Message]) -> _Encoder:
    cached = _encoders.get(cls)
    if cached is not None:
        return cached
    g = _Gen()
    g.emit(0, "def encode(buf, m):")
    for name, spec in cls.__fields__:
        _enc_field(g, 1, spec, f"m.{name}")
    g.emit(1, "return None")
    exec("\n".join(g.lines), g.env)
    encode: _Encoder = g.env["encode"]
    _encoders[cls] = encode
    return encode


def _message_decoder(cls: type[Message]) -> _Decoder:
    cached = _decoders.get(cls)
    if cached is not None:
        return cached
    g = _Gen()
    g.env["cls"] = cls
    g.emit(0, "def decode(data, o):")
    g.emit(1, "n = len(data)")
    names = []
    for index, (_, spec) in enumerate(cls.__fields__):
        var = f"f{index}"
        names.append(var)
        _dec_field(g, 1, spec, var)
    g.emit(1, f"return cls({', '.join(names)}), o")
    exec("\n".join(g.lines), g.env)
    decode: _Decoder = g.env["decode"]
    _decoders[cls] = decode
    return decode


def serialize(msg: Message) -> bytes:
    """Encode ``msg`` as a ROS 2 CDR payload (what rmw puts on the wire)."""
    buf = bytearray(HEADER_LE)
    try:
        _message_encoder(type(msg))(buf, msg)
    except struct.error as exc:
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
    try:
        msg, _ = _message_decoder(cls)(data, 4)
    except struct.error as exc:
        raise CDRError(f"malformed {cls.__typename__} payload: {exc}") from None
    return msg  # type: ignore[no-any-return]
