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

from robomodel.runtime.msg._cdr_strings import (
    CDRError,
    StringsMemo,
    decode_strings,
    encode_strings,
)
from robomodel.runtime.msg._schema import PRIMITIVES, Array, Message, Seq, Spec

__all__ = ["CDRError", "deserialize", "prepare", "serialize"]

HEADER_LE = b"\x00\x01\x00\x00"
_M = TypeVar("_M", bound=Message)

_Encoder = Callable[[bytearray, Any], None]
_Decoder = Callable[[bytes, int], tuple[Any, int]]
_encoders: dict[type[Message], _Encoder] = {}
_decoders: dict[type[Message], _Decoder] = {}


# -- runtime helpers used by the generated code ----------------------------------------------


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
            "_encode_strings": encode_strings,
            "_decode_strings": decode_strings,
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


class _Run:
    """Consecutive fixed-size values packed or unpacked with one ``struct`` call.

    The generator tracks what it knows about the offset statically (``offset = r mod m``,
    relative to the first byte after the header), so CDR's alignment padding inside a run
    becomes ``x`` pad bytes of the format; where the offset is not known (after a string or a
    sequence) the run ends and the padding is computed at run time.
    """

    def __init__(self, modulus: int) -> None:
        self.fmt: list[str] = []
        self.items: list[str] = []  # encode: value expressions; decode: target names
        self.size = 0
        self.m = modulus
        self.r = 0

    def forget(self, modulus: int = 1) -> None:
        """The offset is now only known to be a multiple of ``modulus``."""
        self.m, self.r = modulus, 0


def _add_prim(
    g: _Gen, d: int, run: _Run, code: str, size: int, item: str, count: int, enc: bool
) -> None:
    if size > 1 and run.m % size:  # alignment unknown here: pad at run time
        _flush(g, d, run, enc)
        if enc:
            g.emit(d, f"r = (len(buf) - 4) & {size - 1}")
            g.emit(d, f"if r: buf += b'\\x00' * ({size} - r)")
        else:
            g.emit(d, f"o += (-(o - 4)) & {size - 1}")
        run.forget(size)
    pad = (-run.r) % size if size > 1 else 0
    if pad:
        run.fmt.append(f"{pad}x")
    run.fmt.append(f"{count}{code}" if count > 1 else code)
    run.items.append(item)
    run.size += pad + size * count
    run.r = (run.r + pad + size * count) % run.m


def _flush(g: _Gen, d: int, run: _Run, enc: bool, *, whole: str | None = None) -> None:
    """Emit the pending run. Decoding with ``whole``: the run's last item is a fixed array of
    that name, unpacked as a list after the run's other values."""
    if not run.fmt:
        return
    packer = struct.Struct("<" + "".join(run.fmt))
    if enc:
        g.emit(d, f"buf += {g.ref(packer.pack, 'pk')}({', '.join(run.items)})")
    else:
        g.emit(d, f"if o + {run.size} > n: raise CDRError(f'payload truncated at offset {{o}}')")
        unpack = f"{g.ref(packer.unpack_from, 'up')}(data, o)"
        if whole is not None:
            g.emit(d, f"[{', '.join([*run.items[:-1], '*' + whole])}] = {unpack}")
        else:
            g.emit(d, f"{', '.join(run.items)}{',' if len(run.items) == 1 else ''} = {unpack}")
        g.emit(d, f"o += {run.size}")
    run.fmt, run.items, run.size = [], [], 0


def _after_prim_seq(run: _Run, size: int) -> None:
    # An empty sequence ends after its 4-byte count; a non-empty one after its elements.
    run.forget(min(size, 4) if size > 1 else 1)


def _wire(spec: Spec) -> Spec:
    """A bounded string (``string<=N``) is a string on the wire."""
    return "string" if isinstance(spec, str) and spec.startswith("string<=") else spec


def _enc_field(g: _Gen, d: int, run: _Run, spec: Spec, expr: str) -> None:
    spec = _wire(spec)
    if isinstance(spec, str):
        if spec == "string":  # inline: its length joins the run before it
            data = g.name("b")
            g.emit(d, f"{data} = {expr}.encode('utf-8')")
            _add_prim(g, d, run, "I", 4, f"len({data}) + 1", 1, True)
            _flush(g, d, run, True)
            g.emit(d, f"buf += {data}")
            g.emit(d, "buf.append(0)")
            run.forget()
            return
        code, size, _ = PRIMITIVES[spec]
        _add_prim(g, d, run, code, size, expr, 1, True)
        return
    if isinstance(spec, (Seq, Array)):
        item = _wire(spec.item)
        seq = g.name("s")
        if item == "string":
            _enc_strings(g, d, run, spec, expr)
            return
        if isinstance(spec, Array):
            g_expr = f"_fixed({expr}, {spec.size})"
            if isinstance(item, str) and item != "string":
                code, size, _ = PRIMITIVES[item]
                if spec.size:
                    _add_prim(g, d, run, code, size, "*" + g_expr, spec.size, True)
                return
            _flush(g, d, run, True)
            g.emit(d, f"{seq} = {g_expr}")
        else:
            _flush(g, d, run, True)
            g.emit(d, f"{seq} = {expr}")
            _add_prim(g, d, run, "I", 4, f"len({seq})", 1, True)
            _flush(g, d, run, True)
            if isinstance(item, str) and item != "string":
                code, size, _ = PRIMITIVES[item]
                if code == "B":  # uint8[] (images, point clouds): bytes() is 20x faster
                    g.emit(d, f"buf += bytes({seq})")  # no `if seq`: numpy has no truth value
                    _after_prim_seq(run, size)
                    return
                g.emit(d, f"if {seq}:")
                if size > 1:
                    g.emit(d + 1, f"r = (len(buf) - 4) & {size - 1}")
                    g.emit(d + 1, f"if r: buf += b'\\x00' * ({size} - r)")
                g.emit(d + 1, f"buf += struct.pack('<%d{code}' % len({seq}), *{seq})")
                _after_prim_seq(run, size)
                return
        var = g.name("v")
        g.emit(d, f"for {var} in {seq}:")
        inner = _Run(1)
        _enc_field(g, d + 1, inner, item, var)
        _flush(g, d + 1, inner, True)
        g.emit(d + 1, "pass")
        run.forget()
        return
    if not spec.__fields__:  # rosidl's uint8 structure_needs_at_least_one_member
        _add_prim(g, d, run, "B", 1, "0", 1, True)
        return
    local = g.name("m")  # a nested message: its fields inline, through one local name
    g.emit(d, f"{local} = {expr}")
    for name, field_spec in spec.__fields__:
        _enc_field(g, d, run, field_spec, f"{local}.{name}")


def _enc_strings(g: _Gen, d: int, run: _Run, spec: Seq | Array, expr: str) -> None:
    """Emit the encoding of a ``string[]`` (through its memo) or a ``string[N]``."""
    _flush(g, d, run, True)
    if isinstance(spec, Array):
        g.emit(d, f"_encode_strings(buf, _fixed({expr}, {spec.size}))")
    else:
        g.emit(d, "r = (len(buf) - 4) & 3")  # the count's alignment; the memo writes it
        g.emit(d, "if r: buf += b'\\x00' * (4 - r)")
        g.emit(d, f"{g.ref(StringsMemo(), 'sm')}.encode(buf, {expr})")
    run.forget()


def _dec_field(g: _Gen, d: int, run: _Run, spec: Spec) -> str:
    """Emit the decoding of one field; return the expression of its value (valid after the
    run is flushed)."""
    spec = _wire(spec)
    if isinstance(spec, str):
        var = g.name("f")
        if spec == "string":  # inline: its length joins the run before it
            length, end = g.name("z"), g.name("e")
            _add_prim(g, d, run, "I", 4, length, 1, False)
            _flush(g, d, run, False)
            g.emit(d, f"{end} = o + {length}")
            truncated = (
                f"CDRError(f'payload truncated: string of {{{length}}} bytes at offset {{o}}')"
            )
            g.emit(d, f"if {end} > n: raise {truncated}")
            g.emit(d, f"{var} = data[o : {end} - 1].decode('utf-8')")  # length 0: '' as well
            g.emit(d, f"o = {end}")
            run.forget()
            return var
        code, size, _ = PRIMITIVES[spec]
        _add_prim(g, d, run, code, size, var, 1, False)
        return var
    if isinstance(spec, (Seq, Array)):
        item = _wire(spec.item)
        target, count = g.name("f"), g.name("c")
        if isinstance(spec, Array) and isinstance(item, str) and item != "string":
            code, size, _ = PRIMITIVES[item]
            if code == "B":  # uint8[N]: bytes, as uint8[] below
                return _dec_fixed_bytes(g, d, run, target, spec.size)
            if not spec.size:
                return "[]"
            _add_prim(g, d, run, code, size, target, spec.size, False)
            _flush(g, d, run, False, whole=target)  # the values as one list
            return target
        _flush(g, d, run, False)
        if isinstance(spec, Array):
            g.emit(d, f"{count} = {spec.size}")
        else:
            g.emit(d, f"{count}, o = _count(data, o)")
            run.forget(4)
        if isinstance(item, str) and item != "string":
            code, size, _ = PRIMITIVES[item]
            g.emit(d, f"if {count}:")
            if size > 1:
                g.emit(d + 1, f"o += (-(o - 4)) & {size - 1}")
            g.emit(
                d + 1,
                f"if o + {count} * {size} > n: raise CDRError(f'payload truncated at offset {{o}}')",
            )
            if code == "B":  # bytes, as rospy gives uint8[]: no list of ints to build
                g.emit(d + 1, f"{target} = bytes(data[o : o + {count}])")
            else:
                g.emit(
                    d + 1, f"{target} = list(struct.unpack_from('<%d{code}' % {count}, data, o))"
                )
            g.emit(d + 1, f"o += {count} * {size}")
            g.emit(d, "else:")
            g.emit(d + 1, f"{target} = " + ("b''" if code == "B" else "[]"))
            _after_prim_seq(run, size)
            return target
        if item == "string":
            g.emit(d, f"{target}, o = {g.ref(StringsMemo(), 'sm')}.decode(data, o, {count})")
            run.forget()
            return target
        g.emit(d, f"{target} = []")
        g.emit(d, f"for _ in range({count}):")
        inner = _Run(1)
        value = _dec_field(g, d + 1, inner, item)
        _flush(g, d + 1, inner, False)
        g.emit(d + 1, f"{target}.append({value})")
        run.forget()
        return target
    if not spec.__fields__:  # rosidl's one-byte placeholder, read and dropped
        _add_prim(g, d, run, "B", 1, g.name("pad"), 1, False)
        return f"{g.ref(spec, 'T')}()"
    args = [_dec_field(g, d, run, field_spec) for _, field_spec in spec.__fields__]
    return f"{g.ref(spec, 'T')}({', '.join(args)})"


def _dec_fixed_bytes(g: _Gen, d: int, run: _Run, target: str, size: int) -> str:
    """Emit the decoding of a ``uint8[size]`` array as one slice of the payload."""
    _flush(g, d, run, False)
    g.emit(d, f"if o + {size} > n: raise CDRError(f'payload truncated at offset {{o}}')")
    g.emit(d, f"{target} = bytes(data[o : o + {size}])")
    g.emit(d, f"o += {size}")
    run.r = (run.r + size) % run.m  # bytes need no alignment: the offset stays known
    return target


def _message_encoder(cls: type[Message]) -> _Encoder:
    cached = _encoders.get(cls)
    if cached is not None:
        return cached
    g = _Gen()
    g.emit(0, "def encode(buf, m):")
    run = _Run(8)  # the message starts right after the header: offset 0
    _enc_field(g, 1, run, cls, "m")
    _flush(g, 1, run, True)
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
    g.emit(0, "def decode(data, o):")
    g.emit(1, "n = len(data)")
    run = _Run(8)
    value = _dec_field(g, 1, run, cls)
    _flush(g, 1, run, False)
    g.emit(1, f"return {value}, o")
    exec("\n".join(g.lines), g.env)
    decode: _Decoder = g.env["decode"]
    _decoders[cls] = decode
    return decode


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
