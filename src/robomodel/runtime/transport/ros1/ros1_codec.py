"""ROS 1 serialization of robomodel's messages, generated per type from the ROS 1 definition.

ROS 1's wire format (genpy's serializer): little-endian, no alignment; a string is a uint32
byte count and UTF-8 bytes; a variable-length array a uint32 count then its elements; a
fixed-size array its elements only; ``time`` two uint32 (secs, nsecs), ``duration`` two int32.

The generated encoder walks the ROS 1 definition and reads each field from the robomodel
message by name (``Field`` says where a name or the value differs); runs of fixed-size values
are packed with one ``struct`` call. A ROS 1 field the robomodel type lacks is written as its
default; a robomodel field ROS 1 lacks is not written. The decoder builds the robomodel message;
a nested ROS 1 type robomodel has no class for becomes a ``SimpleNamespace``. Every count and
length is checked against the bytes left before anything is allocated.
"""

from __future__ import annotations

import struct
import types
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from robomodel.errors import RobomodelError
from robomodel.runtime.msg import Message
from robomodel.runtime.msg._source_gen import SourceGen

__all__ = ["Field", "Ros1CodecError", "make_codec"]

PRIMITIVES = {
    "bool": ("?", 1), "int8": ("b", 1), "byte": ("b", 1), "uint8": ("B", 1), "char": ("B", 1),
    "int16": ("h", 2), "uint16": ("H", 2), "int32": ("i", 4), "uint32": ("I", 4),
    "int64": ("q", 8), "uint64": ("Q", 8), "float32": ("f", 4), "float64": ("d", 8),
}  # fmt: skip
TIME, DURATION = "builtin_interfaces/msg/Time", "builtin_interfaces/msg/Duration"
HEADER = "std_msgs/msg/Header"
PLACEHOLDER = (
    "structure_needs_at_least_one_member"  # rosbags' for an empty message: not on ROS 1's wire
)


class Ros1CodecError(RobomodelError):
    """Bytes that are not a valid ROS 1 message of the type, or a value that does not fit."""


@dataclass(frozen=True)
class Field:
    """Where a ROS 1 field's value comes from: robomodel field ``name``, through ``to_ros1``
    (encode) and ``from_ros1`` (decode) when the values differ."""

    name: str
    to_ros1: Callable[[Any], Any] | None = None
    from_ros1: Callable[[Any], Any] | None = None


Fielddefs = dict[str, tuple[Any, list[tuple[str, Any]]]]
Lookup = Callable[[str, str], "Field | None"]  # (ros1 type, ros1 field) -> special mapping


def _count(data: bytes, o: int, item_size: int) -> tuple[int, int]:
    if o + 4 > len(data):
        raise Ros1CodecError(f"truncated at byte {o}: an array's length is cut off")
    (count,) = struct.unpack_from("<I", data, o)
    if count * item_size > len(data) - o - 4:
        raise Ros1CodecError(f"an array of {count} elements at byte {o} overruns the message")
    return count, o + 4


def _fixed(values: Any, size: int) -> list[Any]:
    items = list(values)
    if len(items) != size:
        raise Ros1CodecError(f"a fixed array needs {size} values, got {len(items)}")
    return items


class _Gen(SourceGen):
    def __init__(self, defs: Fielddefs, classes: Callable[[str], Any], special: Lookup) -> None:
        super().__init__(
            {
                "struct": struct, "Ros1CodecError": Ros1CodecError, "_count": _count,
                "_fixed": _fixed, "NS": types.SimpleNamespace,
            }
        )  # fmt: skip
        self.defs = defs
        self.classes = classes  # ros1 type name -> robomodel class or None
        self.special = special
        self.fmt: list[str] = []
        self.items: list[str] = []

    # -- runs of fixed-size values --------------------------------------------------------------
    def prim(self, code: str, item: str) -> None:
        self.fmt.append(code)
        self.items.append(item)

    def flush(self, d: int, enc: bool) -> None:
        if not self.fmt:
            return
        packer = struct.Struct("<" + "".join(self.fmt))
        if enc:
            self.emit(d, f"buf += {self.ref(packer.pack, 'pk')}({', '.join(self.items)})")
        else:
            self.emit(
                d, f"if o + {packer.size} > n: raise Ros1CodecError(f'truncated at byte {{o}}')"
            )
            targets = ", ".join(self.items) + ("," if len(self.items) == 1 else "")
            self.emit(d, f"{targets} = {self.ref(packer.unpack_from, 'up')}(data, o)")
            self.emit(d, f"o += {packer.size}")
        self.fmt, self.items = [], []


def _kind(desc: Any) -> tuple[int, Any]:
    return int(desc[0]), desc[1]


# -- encoding ---------------------------------------------------------------------------------
def _enc(g: _Gen, d: int, desc: Any, expr: str, top: bool) -> None:
    kind, rest = _kind(desc)
    if kind == 1:  # base
        name = rest[0]
        if name == "string":  # inline: its length joins the run of fixed-size values
            data = g.name("b")
            g.emit(d, f"{data} = {expr}.encode()")
            g.prim("I", f"len({data})")
            g.flush(d, True)
            g.emit(d, f"buf += {data}")
        else:
            g.prim(PRIMITIVES[name][0], expr)
    elif kind == 2:  # a message type
        _enc_message(g, d, rest, expr, top)
    else:
        _enc_array(g, d, kind, rest, expr)


def _enc_array(g: _Gen, d: int, kind: int, rest: Any, expr: str) -> None:
    item, size = rest
    ikind, irest = _kind(item)
    seq = g.name("s")
    g.flush(d, True)
    if kind == 3:  # fixed size
        g.emit(d, f"{seq} = _fixed({expr}, {size})")
    else:
        g.emit(d, f"{seq} = {expr}")
        g.emit(d, f"buf += struct.pack('<I', len({seq}))")
    if ikind == 1 and irest[0] != "string":
        code = PRIMITIVES[irest[0]][0]
        if code == "B":  # uint8[] (images): bytes() is 20x faster than struct.pack
            g.emit(d, f"buf += bytes({seq})")
        else:
            g.emit(d, f"buf += struct.pack('<%d{code}' % len({seq}), *{seq})")
        return
    var = g.name("v")
    g.emit(d, f"for {var} in {seq}:")
    _enc(g, d + 1, item, var, False)
    g.flush(d + 1, True)
    g.emit(d + 1, "pass")


def _enc_message(g: _Gen, d: int, type_name: str, expr: str, top: bool) -> None:
    if type_name in (TIME, DURATION):
        code = "I" if type_name == TIME else "i"
        local = g.name("t")  # names are unique: values of a pending run stay valid
        g.emit(d, f"{local} = {expr}")
        g.prim(code, f"{local}.sec")
        g.prim(code, f"{local}.nanosec")
        return
    local = g.name("m")
    g.emit(d, f"{local} = {expr}")
    ours = g.classes(type_name)
    names = {n for n, _ in ours.__fields__} if ours is not None else None
    for field_name, desc in g.defs[type_name][1]:
        if field_name == PLACEHOLDER:
            continue
        if type_name == HEADER and field_name == "seq":
            g.prim("I", "seq" if top else "0")
            continue
        special = g.special(type_name, field_name)
        source = special.name if special is not None else field_name
        if names is not None and source not in names:
            _enc(g, d, desc, g.ref(_default(g.defs, desc), "dflt") + "()", False)
            continue
        value = f"{local}.{source}"
        if special is not None and special.to_ros1 is not None:
            value = f"{g.ref(special.to_ros1, 'cv')}({value})"
        # rospy numbers the messages in the ``header`` of the message published
        _enc(g, d, desc, value, top and tuple(desc) == (2, HEADER))


def _default(defs: Fielddefs, desc: Any) -> Callable[[], Any]:
    kind, rest = _kind(desc)
    if kind == 1:
        value: Any = "" if rest[0] == "string" else (False if rest[0] == "bool" else 0)
        return lambda: value
    if kind == 3:
        item = _default(defs, rest[0])
        return lambda: [item() for _ in range(rest[1])]
    if kind == 4:
        return list
    if rest in (TIME, DURATION):
        return lambda: types.SimpleNamespace(sec=0, nanosec=0)
    fields = [(n, _default(defs, f)) for n, f in defs[rest][1]]
    return lambda: types.SimpleNamespace(**{n: make() for n, make in fields})


# -- decoding ---------------------------------------------------------------------------------
def _dec(g: _Gen, d: int, desc: Any) -> str:
    kind, rest = _kind(desc)
    if kind == 1:
        var = g.name("f")
        if rest[0] == "string":  # inline: its length joins the run of fixed-size values
            size = g.name("z")
            g.prim("I", size)
            g.flush(d, False)
            overrun = f"f'a string of {{{size}}} bytes at byte {{o}} overruns the message'"
            g.emit(d, f"if {size} > n - o: raise Ros1CodecError({overrun})")
            g.emit(d, f"{var} = data[o : o + {size}].decode('utf-8', 'replace')")
            g.emit(d, f"o += {size}")
        else:
            g.prim(PRIMITIVES[rest[0]][0], var)
        return var
    if kind == 2:
        return _dec_message(g, d, rest)
    item, size = rest
    ikind, irest = _kind(item)
    target, count = g.name("a"), g.name("c")
    g.flush(d, False)
    primitive = ikind == 1 and irest[0] != "string"
    item_size = PRIMITIVES[irest[0]][1] if primitive else 1
    if kind == 3:
        g.emit(d, f"{count} = {size}")
    else:
        g.emit(d, f"{count}, o = _count(data, o, {item_size})")
    if primitive:
        code = PRIMITIVES[irest[0]][0]
        g.emit(
            d, f"if o + {count} * {item_size} > n: raise Ros1CodecError(f'truncated at byte {{o}}')"
        )
        if code == "B":  # uint8[]/char[]: bytes, as rospy (genpy) gives them
            g.emit(d, f"{target} = bytes(data[o : o + {count}])")
        else:
            g.emit(d, f"{target} = list(struct.unpack_from('<%d{code}' % {count}, data, o))")
        g.emit(d, f"o += {count} * {item_size}")
        return target
    g.emit(d, f"{target} = []")
    g.emit(d, f"for _ in range({count}):")
    value = _dec(g, d + 1, item)
    g.flush(d + 1, False)
    g.emit(d + 1, f"{target}.append({value})")
    return target


def _dec_message(g: _Gen, d: int, type_name: str) -> str:
    if type_name in (TIME, DURATION):
        code = "I" if type_name == TIME else "i"
        sec, nsec = g.name("f"), g.name("f")
        g.prim(code, sec)
        g.prim(code, nsec)
        ours = g.classes(type_name)
        return f"{g.ref(_maker(ours), 'T')}({sec}, {nsec})"
    ours = g.classes(type_name)
    names = {n for n, _ in ours.__fields__} if ours is not None else None
    args = []
    kept = []  # a face's fields that only ROS 1 has (genpy's Header.seq), given by keyword
    for field_name, desc in g.defs[type_name][1]:
        if field_name == PLACEHOLDER:
            continue
        value = _dec(g, d, desc)
        special = g.special(type_name, field_name)
        target = special.name if special is not None else field_name
        if names is not None and target not in names:
            if target in getattr(ours, "__slots__", ()) and hasattr(ours, "__from_fields__"):
                kept.append(f"{target}={value}")
            continue
        if special is not None and special.from_ros1 is not None:
            value = f"{g.ref(special.from_ros1, 'cv')}({value})"
        args.append((target, value))
    if ours is None:  # a dict display: a call's keywords take time quadratic in their number
        return f"NS(**{{{', '.join(f'{t!r}: {v}' for t, v in args)}}})"
    # Positional while the ROS 1 fields come in the class's order (all of them, for a type
    # built from the ROS 1 definition), keywords for the rest: CPython compiles a call's
    # keywords in time quadratic in their number (a 10,000-field type took seconds).
    order = [n for n, _ in ours.__fields__]
    cut = 0
    while cut < min(len(args), len(order)) and args[cut][0] == order[cut]:
        cut += 1
    parts = [v for _, v in args[:cut]] + [f"{t}={v}" for t, v in args[cut:]] + kept
    return f"{g.ref(_maker(ours), 'T')}({', '.join(parts)})"


def _maker(cls: Any) -> Any:
    """What builds an instance of ``cls`` from its field values: a client library's face of a
    type has its own (``__from_fields__``, see msg._from_definition.MessageFlavour)."""
    return getattr(cls, "__from_fields__", cls)


Encoder = Callable[[Message, int], bytes]
Decoder = Callable[[bytes], Message]


def make_codec(
    type_name: str, defs: Fielddefs, classes: Callable[[str], Any], special: Lookup
) -> tuple[Encoder, Decoder]:
    """The encoder ``(msg, seq) -> bytes`` and decoder ``bytes -> msg`` of ROS 1 type
    ``type_name`` (``pkg/msg/Name`` as rosbags names it)."""
    g = _Gen(defs, classes, special)
    g.emit(0, "def encode(m, seq):")
    g.emit(1, "buf = bytearray()")
    _enc_message(g, 1, type_name, "m", True)
    g.flush(1, True)
    g.emit(1, "return bytes(buf)")
    g.emit(0, "def decode(data):")
    g.emit(1, "n = len(data)")
    g.emit(1, "o = 0")
    value = _dec_message(g, 1, type_name)
    g.flush(1, False)
    g.emit(1, "if o != n: raise Ros1CodecError(f'{n - o} bytes left over after the message')")
    g.emit(1, f"return {value}")
    exec("\n".join(g.lines), g.env)
    raw_encode, raw_decode = g.env["encode"], g.env["decode"]

    def encode(msg: Message, seq: int = 0) -> bytes:
        try:
            return raw_encode(msg, seq)  # type: ignore[no-any-return]
        except (
            struct.error,
            AttributeError,
            TypeError,
            UnicodeEncodeError,
            ValueError,
            OverflowError,
        ) as exc:
            raise Ros1CodecError(
                f"{type_name}: a value does not fit ROS 1's field: {exc}"
            ) from None

    def decode(data: bytes) -> Message:
        try:
            return raw_decode(bytes(data))  # type: ignore[no-any-return]
        except (struct.error, TypeError, ValueError) as exc:
            raise Ros1CodecError(f"malformed ROS 1 {type_name}: {exc}") from None

    return encode, decode
