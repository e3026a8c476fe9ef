"""The CDR encoder of a message type, generated as Python source (cdr.py says how)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from robomodel.runtime.msg._cdr_codegen import (
    ARRAY_FLOAT64,
    Gen,
    Run,
    add_prim,
    after_prim_seq,
    flush,
    wire,
)
from robomodel.runtime.msg._cdr_strings import StringsMemo
from robomodel.runtime.msg.schema import PRIMITIVES, Array, Message, Seq, Spec

__all__ = ["Encoder", "encoders", "message_encoder"]

Encoder = Callable[[bytearray, Any], None]
encoders: dict[type[Message], Encoder] = {}


def _enc_field(g: Gen, d: int, run: Run, spec: Spec, expr: str) -> None:
    """Emit the encoding of the field ``spec`` whose value is ``expr``."""
    spec = wire(spec)
    if spec == "string":  # inline: its length joins the run before it
        data = g.name("b")
        g.emit(d, f"{data} = {expr}.encode('utf-8')")
        add_prim(g, d, run, "I", 4, f"len({data}) + 1", 1, True)
        flush(g, d, run, True)
        g.emit(d, f"buf += {data}")
        g.emit(d, "buf.append(0)")
        run.forget()
    elif isinstance(spec, str):
        code, size, _ = PRIMITIVES[spec]
        if spec == "byte":  # rclpy holds an octet as bytes of length 1
            expr = f"{g.ref(octet, 'oc')}({expr})"
        add_prim(g, d, run, code, size, expr, 1, True)
    elif isinstance(spec, (Seq, Array)):
        _enc_sequence(g, d, run, spec, expr)
    elif not spec.__fields__:  # rosidl's uint8 structure_needs_at_least_one_member
        add_prim(g, d, run, "B", 1, "0", 1, True)
    else:
        local = g.name("m")  # a nested message: its fields inline, through one local name
        g.emit(d, f"{local} = {expr}")
        for name, field_spec in spec.__fields__:
            _enc_field(g, d, run, field_spec, f"{local}.{name}")


def _enc_sequence(g: Gen, d: int, run: Run, spec: Seq | Array, expr: str) -> None:
    """Emit the encoding of a sequence or a fixed array."""
    item = wire(spec.item)
    seq = g.name("s")
    if item == "string":
        _enc_strings(g, d, run, spec, expr)
        return
    primitive = isinstance(item, str)
    if item == "byte":  # rclpy holds an octet sequence as a list of bytes of length 1
        expr = f"{g.ref(octets, 'ocs')}({expr})"
    if isinstance(spec, Array):
        fixed = f"_fixed({expr}, {spec.size})"
        if primitive:
            code, size, _ = PRIMITIVES[item]  # type: ignore[index]
            if spec.size:
                add_prim(g, d, run, code, size, "*" + fixed, spec.size, True)
            return
        flush(g, d, run, True)
        g.emit(d, f"{seq} = {fixed}")
    else:
        flush(g, d, run, True)
        g.emit(d, f"{seq} = {expr}")
        add_prim(g, d, run, "I", 4, f"len({seq})", 1, True)
        flush(g, d, run, True)
        if primitive:
            _enc_primitives(g, d, run, str(item), seq)
            return
    var = g.name("v")
    g.emit(d, f"for {var} in {seq}:")
    inner = Run(1)
    _enc_field(g, d + 1, inner, item, var)
    flush(g, d + 1, inner, True)
    g.emit(d + 1, "pass")
    run.forget()


def octet(value: Any) -> Any:
    """A ``byte`` field's value as the integer CDR writes: robomodel and rospy hold an int,
    rclpy (rosidl's ``octet``) bytes of length 1."""
    return value[0] if value.__class__ is bytes else value


def octets(values: Any) -> Any:
    """A ``byte[]`` field's values as bytes-like: a list of bytes objects (rclpy) joined."""
    if values.__class__ is list and values and values[0].__class__ is bytes:
        return b"".join(values)
    return values


def _enc_primitives(g: Gen, d: int, run: Run, item: str, seq: str) -> None:
    """Emit the encoding of a sequence's primitives (after its count) as one ``struct`` call."""
    code, size, _ = PRIMITIVES[item]
    if code == "B":  # uint8[] (images, point clouds): bytes() is 20x faster
        g.emit(d, f"buf += bytes({seq})")  # no `if seq`: numpy has no truth value
    else:
        g.emit(d, f"if len({seq}):")  # not `if seq`: numpy arrays have no truth value
        if size > 1:
            g.emit(d + 1, f"r = (len(buf) - 4) & {size - 1}")
            g.emit(d + 1, f"if r: buf += b'\\x00' * ({size} - r)")
        if code == "d" and ARRAY_FLOAT64:  # any iterable of numbers; TypeError otherwise
            g.emit(d + 1, f"buf += _array('d', {seq})")
        else:
            g.emit(d + 1, f"buf += struct.pack('<%d{code}' % len({seq}), *{seq})")
    after_prim_seq(run, size)


def _enc_strings(g: Gen, d: int, run: Run, spec: Seq | Array, expr: str) -> None:
    """Emit the encoding of a ``string[]`` (through its memo) or a ``string[N]``."""
    flush(g, d, run, True)
    if isinstance(spec, Array):
        g.emit(d, f"_encode_strings(buf, _fixed({expr}, {spec.size}))")
    else:
        g.emit(d, "r = (len(buf) - 4) & 3")  # the count's alignment; the memo writes it
        g.emit(d, "if r: buf += b'\\x00' * (4 - r)")
        g.emit(d, f"{g.ref(StringsMemo(), 'sm')}.encode(buf, {expr})")
    run.forget()


def message_encoder(cls: type[Message]) -> Encoder:
    cached = encoders.get(cls)
    if cached is not None:
        return cached
    g = Gen()
    g.emit(0, "def encode(buf, m):")
    run = Run(8)  # the message starts right after the header: offset 0
    _enc_field(g, 1, run, cls, "m")
    flush(g, 1, run, True)
    g.emit(1, "return None")
    exec("\n".join(g.lines), g.env)
    encode: Encoder = g.env["encode"]
    encoders[cls] = encode
    return encode
