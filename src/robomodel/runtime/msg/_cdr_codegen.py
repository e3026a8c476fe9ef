"""Code generation for the CDR codecs (cdr.py): the generated source's lines and names, and the
runs of fixed-size values packed or unpacked by one ``struct`` call."""

from __future__ import annotations

import struct
import sys
from array import array
from typing import Any

from robomodel.runtime.msg._cdr_strings import CDRError, encode_strings
from robomodel.runtime.msg._source_gen import SourceGen
from robomodel.runtime.msg.schema import Spec

__all__ = [
    "ARRAY_FLOAT64",
    "Gen",
    "Run",
    "add_prim",
    "after_prim_seq",
    "emit_count",
    "flush",
    "wire",
]


# -- runtime helpers used by the generated code ----------------------------------------------


def _fixed(values: Any, size: int) -> list[Any]:
    items: list[Any] = list(values)
    if len(items) != size:
        raise CDRError(f"fixed array needs {size} values, got {len(items)}")
    return items


# float64[] through array('d') (its bytes are the machine's doubles, so little-endian hosts
# only): no format string to build and look up, no argument tuple of every value. Coded
# cold, once a millisecond, it is a third faster than struct.
ARRAY_FLOAT64 = sys.byteorder == "little"


# -- code generation -------------------------------------------------------------------------


class Gen(SourceGen):
    """Accumulates a CDR codec's source lines and the names they refer to."""

    def __init__(self) -> None:
        super().__init__(
            {
                "struct": struct,
                "CDRError": CDRError,
                "_encode_strings": encode_strings,
                "_fixed": _fixed,
                "_array": array,
                "_u32": struct.Struct("<I").unpack_from,
            }
        )


def emit_count(g: Gen, d: int, count: str) -> None:
    """Emit the reading of a sequence's count at ``o`` (aligned to 4 first) into ``count``,
    inline: a call per sequence was a tenth of a JointState's decoding."""
    g.emit(d, "o += (-(o - 4)) & 3")
    g.emit(d, "if o + 4 > n: raise CDRError(f'payload truncated: sequence length at offset {o}')")
    g.emit(d, f"{count}, = _u32(data, o)")
    g.emit(d, "o += 4")
    too_long = f"CDRError(f'sequence length {{{count}}} exceeds the payload size')"
    g.emit(d, f"if {count} > n: raise {too_long}")


class Run:
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


def add_prim(
    g: Gen, d: int, run: Run, code: str, size: int, item: str, count: int, enc: bool
) -> None:
    if size > 1 and run.m % size:  # alignment unknown here: pad at run time
        flush(g, d, run, enc)
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


def flush(g: Gen, d: int, run: Run, enc: bool, *, whole: str | None = None) -> None:
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


def after_prim_seq(run: Run, size: int) -> None:
    # An empty sequence ends after its 4-byte count; a non-empty one after its elements.
    run.forget(min(size, 4) if size > 1 else 1)


def wire(spec: Spec) -> Spec:
    """A bounded string (``string<=N``) is a string on the wire."""
    return "string" if isinstance(spec, str) and spec.startswith("string<=") else spec
