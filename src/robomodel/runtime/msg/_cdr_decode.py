"""The CDR decoder of a message type, generated as Python source (cdr.py says how)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from robomodel.runtime.msg._cdr_codegen import (
    ARRAY_FLOAT64,
    Gen,
    Run,
    add_prim,
    after_prim_seq,
    emit_count,
    flush,
    wire,
)
from robomodel.runtime.msg._cdr_strings import StringsMemo
from robomodel.runtime.msg.schema import PRIMITIVES, Array, Message, Seq, Spec

__all__ = ["Decoder", "decoders", "message_decoder"]

Decoder = Callable[[bytes, int], tuple[Any, int]]
decoders: dict[type[Message], Decoder] = {}


def _dec_field(g: Gen, d: int, run: Run, spec: Spec) -> str:
    """Emit the decoding of one field; return the expression of its value (valid after the
    run is flushed)."""
    spec = wire(spec)
    if spec == "string":
        return _dec_string(g, d, run)
    if isinstance(spec, str):
        var = g.name("f")
        code, size, _ = PRIMITIVES[spec]
        add_prim(g, d, run, code, size, var, 1, False)
        return var
    if isinstance(spec, (Seq, Array)):
        return _dec_sequence(g, d, run, spec)
    # A client library's face of the type builds its instances its own way (MessageFlavour).
    make = getattr(spec, "__from_fields__", spec)
    if not spec.__fields__:  # rosidl's one-byte placeholder, read and dropped
        add_prim(g, d, run, "B", 1, g.name("pad"), 1, False)
        return f"{g.ref(make, 'T')}()"
    args = [_dec_field(g, d, run, field_spec) for _, field_spec in spec.__fields__]
    return f"{g.ref(make, 'T')}({', '.join(args)})"


def _dec_string(g: Gen, d: int, run: Run) -> str:
    """Emit the decoding of a string: its length joins the run before it."""
    var, length, end = g.name("f"), g.name("z"), g.name("e")
    add_prim(g, d, run, "I", 4, length, 1, False)
    flush(g, d, run, False)
    g.emit(d, f"{end} = o + {length}")
    truncated = f"CDRError(f'payload truncated: string of {{{length}}} bytes at offset {{o}}')"
    g.emit(d, f"if {end} > n: raise {truncated}")
    g.emit(d, f"{var} = data[o : {end} - 1].decode('utf-8')")  # length 0: '' as well
    g.emit(d, f"o = {end}")
    run.forget()
    return var


def _dec_sequence(g: Gen, d: int, run: Run, spec: Seq | Array) -> str:
    """Emit the decoding of a sequence or a fixed array."""
    item = wire(spec.item)
    target, count = g.name("f"), g.name("c")
    primitive = isinstance(item, str) and item != "string"
    if isinstance(spec, Array) and primitive:
        code, size, _ = PRIMITIVES[item]  # type: ignore[index]
        if code == "B":  # uint8[N]: bytes, as uint8[] below
            return _dec_fixed_bytes(g, d, run, target, spec.size)
        if not spec.size:
            return "[]"
        add_prim(g, d, run, code, size, target, spec.size, False)
        flush(g, d, run, False, whole=target)  # the values as one list
        return target
    flush(g, d, run, False)
    if isinstance(spec, Array):
        g.emit(d, f"{count} = {spec.size}")
    else:
        emit_count(g, d, count)
        run.forget(4)
    if primitive:
        _dec_primitives(g, d, run, str(item), target, count)
    elif item == "string":
        g.emit(d, f"{target}, o = {g.ref(StringsMemo(), 'sm')}.decode(data, o, {count})")
        run.forget()
    else:
        g.emit(d, f"{target} = []")
        g.emit(d, f"for _ in range({count}):")
        inner = Run(1)
        value = _dec_field(g, d + 1, inner, item)
        flush(g, d + 1, inner, False)
        g.emit(d + 1, f"{target}.append({value})")
        run.forget()
    return target


def _dec_primitives(g: Gen, d: int, run: Run, item: str, target: str, count: str) -> None:
    """Emit the decoding of ``count`` primitives as one ``struct`` call (uint8: bytes)."""
    code, size, _ = PRIMITIVES[item]
    g.emit(d, f"if {count}:")
    if size > 1:
        g.emit(d + 1, f"o += (-(o - 4)) & {size - 1}")
    end = g.name("e")
    g.emit(d + 1, f"{end} = o + {count} * {size}")
    g.emit(d + 1, f"if {end} > n: raise CDRError(f'payload truncated at offset {{o}}')")
    if code == "B":  # bytes, as rospy gives uint8[]: no list of ints to build
        g.emit(d + 1, f"{target} = bytes(data[o : {end}])")
    elif code == "d" and ARRAY_FLOAT64:
        g.emit(d + 1, f"{target} = _array('d', data[o : {end}]).tolist()")
    else:
        g.emit(d + 1, f"{target} = list(struct.unpack_from('<%d{code}' % {count}, data, o))")
    g.emit(d + 1, f"o = {end}")
    g.emit(d, "else:")
    g.emit(d + 1, f"{target} = " + ("b''" if code == "B" else "[]"))
    after_prim_seq(run, size)


def _dec_fixed_bytes(g: Gen, d: int, run: Run, target: str, size: int) -> str:
    """Emit the decoding of a ``uint8[size]`` array as one slice of the payload."""
    flush(g, d, run, False)
    g.emit(d, f"if o + {size} > n: raise CDRError(f'payload truncated at offset {{o}}')")
    g.emit(d, f"{target} = bytes(data[o : o + {size}])")
    g.emit(d, f"o += {size}")
    run.r = (run.r + size) % run.m  # bytes need no alignment: the offset stays known
    return target


def message_decoder(cls: type[Message]) -> Decoder:
    cached = decoders.get(cls)
    if cached is not None:
        return cached
    g = Gen()
    g.emit(0, "def decode(data, o):")
    g.emit(1, "n = len(data)")
    run = Run(8)
    value = _dec_field(g, 1, run, cls)
    flush(g, 1, run, False)
    g.emit(1, f"return {value}, o")
    exec("\n".join(g.lines), g.env)
    decode: Decoder = g.env["decode"]
    decoders[cls] = decode
    return decode
