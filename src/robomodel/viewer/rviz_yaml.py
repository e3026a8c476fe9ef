"""YAML text as RViz writes its ``.rviz`` files (rviz's ``YamlConfigWriter`` on yaml-cpp).

Block style throughout, two spaces per level, a sequence under a key indented by two
(``Displays:\\n    - Alpha: 0.5``), the keys of every map sorted as RViz's ``QMap`` keeps them
(by UTF-16 code unit: ``Alpha`` < ``Value`` < ``base_link``), an empty map or sequence on the
line below its key (``Namespaces:\\n  {}``), null as ``~``, the empty string as ``""``. Every
value reads back with :func:`yaml.safe_load` as the value written, so read -> write -> read
is the identity.
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping, Sequence
from typing import Any

import yaml

__all__ = ["dump_rviz_yaml"]

# Not printable in a YAML stream (surrogates, BOM, U+FFFE/F), or line breaks (U+2028/9).
_UNSAFE = re.compile("[\\ud800-\\udfff\\u2028\\u2029\\ufeff\\ufffe\\uffff]")
# Plain scalars only from characters that cannot start or end a YAML indicator; the rest is
# double-quoted (yaml-cpp quotes where a plain scalar would read back differently, too).
_PLAIN = re.compile(r"[A-Za-z0-9_<(./][A-Za-z0-9_ <>()./;,+=-]*")


def _is_collection(value: Any) -> bool:
    return isinstance(value, Mapping) or (
        isinstance(value, Sequence) and not isinstance(value, str | bytes)
    )


def _float_text(value: float) -> str:
    if math.isnan(value):
        return ".nan"
    if math.isinf(value):
        return ".inf" if value > 0 else "-.inf"
    if value.is_integer() and abs(value) < 1e15:
        return str(int(value))  # RViz writes 10, not 10.0
    text = repr(value)
    if "e" in text and "." not in text:  # YAML 1.1 floats need a dot: 1e-05 -> 1.0e-05
        mantissa, exponent = text.split("e")
        text = f"{mantissa}.0e{exponent}"
    return text


def _string_text(value: str) -> str:
    if value and _PLAIN.fullmatch(value) and not value.endswith(" "):
        try:
            if yaml.safe_load(value) == value:
                return value
        except yaml.YAMLError:
            pass
    return '"' + "".join(_escape(c) for c in value) + '"'


def _escape(char: str) -> str:
    """One character of a double-quoted YAML scalar: printable as is, the rest escaped."""
    if char in ('"', "\\"):
        return "\\" + char
    code = ord(char)
    if 0x20 <= code <= 0x7E or (code >= 0xA0 and not _UNSAFE.match(char)):
        return char
    if code < 0x100:
        return f"\\x{code:02x}"
    return f"\\u{code:04x}" if code < 0x10000 else f"\\U{code:08x}"


def _scalar(value: Any) -> str:
    if value is None:
        return "~"
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        return _float_text(value)
    return _string_text(str(value))


def _key_order(key: Any) -> bytes:
    return str(key).encode("utf-16-be", "surrogatepass")


def _block(node: Any, indent: int) -> list[str]:
    """The lines of a non-empty map or sequence whose entries start at column ``indent``."""
    pad = " " * indent
    lines: list[str] = []
    if isinstance(node, Mapping):
        for key in sorted(node, key=_key_order):
            value = node[key]
            head = f"{pad}{_scalar(key)}:"
            if not _is_collection(value):
                lines.append(f"{head} {_scalar(value)}")
            elif not value:
                lines += [head, f"{pad}  {'{}' if isinstance(value, Mapping) else '[]'}"]
            else:
                lines += [head, *_block(value, indent + 2)]
        return lines
    for item in node:
        if not _is_collection(item):
            lines.append(f"{pad}- {_scalar(item)}")
        elif not item:
            lines.append(f"{pad}- {'{}' if isinstance(item, Mapping) else '[]'}")
        else:
            inner = _block(item, indent + 2)
            lines += [f"{pad}- {inner[0][indent + 2 :]}", *inner[1:]]
    return lines


def dump_rviz_yaml(tree: Mapping[str, Any]) -> str:
    """The text of an ``.rviz`` file holding ``tree`` (maps, sequences, scalars)."""
    if not tree:
        return "{}\n"
    return "\n".join(_block(tree, 0)) + "\n"
