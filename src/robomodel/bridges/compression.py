"""rosbridge's compressions of the messages it sends: ``cbor``, ``cbor-raw`` and ``png``.

A client picks one per ``subscribe`` (``compression``); the messages then go as:

- ``cbor``: the ``publish`` operation as one binary CBOR frame (RFC 8949), the message's values
  as rosbridge's ``cbor_conversion`` gives them: numeric arrays as RFC 8746 typed arrays (a tag
  and the little-endian bytes: 69 ``uint16``, 70 ``uint32``, 71 ``uint64``, 72 ``int8``, 77
  ``int16``, 78 ``int32``, 79 ``int64``, 85 ``float32``, 86 ``float64``), ``uint8``/``char``
  arrays as byte strings, times as ``{sec, nanosec}`` (ROS 2) or ``{secs, nsecs}`` (ROS 1).
  Fixed-size arrays go as typed arrays too (rosbridge fails on them). Non-finite floats stay
  floats (CBOR holds them).
- ``cbor-raw``: ``{"op": "publish", "topic", "msg": {"secs", "nsecs", "bytes"}}`` in CBOR, the
  bytes the message's serialisation on the bus (CDR on ROS 2, ROS 1's on ROS 1), the time the
  bridge's clock when it sent it.
- ``png``: the ``publish`` operation's JSON text as the pixels of a square-ish RGB PNG image,
  padded with ``\\n``, base64 in ``{"op": "png", "data"}`` (rosbridge's ``pngcompression``).

Transcribed from github:RobotWebTools/rosbridge_suite (ros2 branch, commit c1bfc2f):
``rosbridge_library/internal/cbor_conversion.py``, ``pngcompression.py`` and
``capabilities/subscribe.py`` (``publish``). The CBOR encoder is ``cbor2`` (the ``bridges``
extra); the PNG writer is the standard library's ``zlib`` (a PNG of one IDAT chunk).
"""

from __future__ import annotations

import base64
import math
import struct
import zlib
from typing import Any, Literal

from robomodel.bridges.json_mapping import Dialect
from robomodel.errors import MissingDependencyError
from robomodel.runtime.msg import Message
from robomodel.runtime.msg.schema import Array, Seq, Spec, is_byte_array

__all__ = [
    "COMPRESSIONS",
    "Compression",
    "cbor_frame",
    "cbor_raw_frame",
    "cbor_values",
    "png_frame",
]

Compression = Literal["none", "png", "cbor", "cbor-raw"]
COMPRESSIONS: tuple[Compression, ...] = ("none", "png", "cbor", "cbor-raw")

# RFC 8746's typed-array tags (little endian), as rosbridge's TAGGED_ARRAY_FORMATS
_TAGGED: dict[str, tuple[int, str]] = {
    "uint16": (69, "H"),
    "uint32": (70, "I"),
    "uint64": (71, "Q"),
    "int8": (72, "b"),
    "int16": (77, "h"),
    "int32": (78, "i"),
    "int64": (79, "q"),
    "float32": (85, "f"),
    "float64": (86, "d"),
}
_TIME_TYPES = ("builtin_interfaces/msg/Time", "builtin_interfaces/msg/Duration")


def _cbor2() -> Any:
    try:
        import cbor2
    except ImportError:
        raise MissingDependencyError("cbor2", "bridges", "rosbridge's cbor compression") from None
    return cbor2


def cbor_values(msg: Message, dialect: Dialect) -> dict[str, Any]:
    """``msg``'s values as rosbridge's ``extract_cbor_values`` makes them (module docstring)."""
    tag = _cbor2().CBORTag
    return _values(msg, dialect, tag)


def _values(msg: Message, dialect: Dialect, tag: Any) -> dict[str, Any]:
    if dialect == "ros1" and msg.__typename__ in _TIME_TYPES:
        return {"secs": int(msg.sec), "nsecs": int(msg.nanosec)}  # type: ignore[attr-defined]
    return {name: _value(spec, getattr(msg, name), dialect, tag) for name, spec in msg.__fields__}


def _value(spec: Spec, value: Any, dialect: Dialect, tag: Any) -> Any:
    if isinstance(spec, str):
        return value
    if is_byte_array(spec):
        return bytes(value)
    if isinstance(spec, Seq | Array):
        item = spec.item
        if isinstance(item, str):
            tagged = _TAGGED.get(item)
            if tagged is not None:
                number, code = tagged
                return tag(number, struct.pack(f"<{len(value)}{code}", *value))
            return list(value)  # bool and string arrays
        return [_values(element, dialect, tag) for element in value]
    return _values(value, dialect, tag)


def cbor_frame(topic: str, msg: Message, dialect: Dialect) -> bytes:
    """The ``publish`` operation of ``msg`` on ``topic`` as one CBOR frame."""
    cbor2 = _cbor2()
    body = {"op": "publish", "topic": topic, "msg": _values(msg, dialect, cbor2.CBORTag)}
    return bytes(cbor2.dumps(body))


def cbor_raw_frame(topic: str, serialized: bytes, now_ns: int) -> bytes:
    """The ``publish`` operation of a message's bus serialisation, stamped ``now_ns``."""
    secs, nsecs = divmod(now_ns, 1_000_000_000)
    body = {"op": "publish", "topic": topic,
            "msg": {"secs": secs, "nsecs": nsecs, "bytes": bytes(serialized)}}  # fmt: skip
    return bytes(_cbor2().dumps(body))


def png_frame(text: str) -> str:
    """``text`` (an operation's JSON) as rosbridge's ``{"op": "png", "data"}`` JSON frame."""
    return '{"op": "png", "data": "' + png_encode(text) + '"}'


def png_encode(text: str) -> str:
    """rosbridge's ``pngcompression.encode``: the UTF-8 bytes as the pixels of an RGB image
    ``floor(sqrt(n / 3))`` wide (at least 1), padded with ``\\n``; the PNG in base64."""
    data = text.encode("utf-8")
    width = max(1, math.floor(math.sqrt(len(data) / 3.0)))
    height = max(1, math.ceil(len(data) / 3.0 / width))
    data += b"\n" * (width * height * 3 - len(data))
    row = width * 3
    # filter type 0 (none) before each row
    raw = b"".join(b"\x00" + data[y * row : (y + 1) * row] for y in range(height))
    header = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)  # 8-bit RGB
    png = b"\x89PNG\r\n\x1a\n" + _chunk(b"IHDR", header)
    png += _chunk(b"IDAT", zlib.compress(raw, 6)) + _chunk(b"IEND", b"")
    return base64.b64encode(png).decode("ascii")


def _chunk(kind: bytes, body: bytes) -> bytes:
    return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))
