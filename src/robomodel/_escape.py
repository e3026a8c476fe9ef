"""Printing text that came from another process: control characters escaped.

A node, topic, service or parameter name is chosen by whoever declared it, and a peer can put
``ESC ]0;...BEL`` (retitle the terminal), ``ESC[31m`` (recolour it), a carriage return (overwrite
the line) or a bidirectional override in one. Everything the CLI lists and every log line that
names such a thing goes through :func:`escape_name`, which writes each character that is not
printable as Python writes it in a string literal (``\\x1b``, ``\\u202e``) and keeps printable
Unicode (``/bras_robotique``, ``/ロボット``) as it is. A backslash is doubled, so that a name
spelling ``\\x1b`` out cannot pass for an escaped one.
"""

from __future__ import annotations

from collections.abc import Iterable

__all__ = ["escape_name", "escape_names"]


def _escape_char(char: str) -> str:
    if char == "\\":
        return "\\\\"
    if char.isprintable():
        return char
    code = ord(char)
    if code < 0x100:
        return f"\\x{code:02x}"
    if code < 0x10000:
        return f"\\u{code:04x}"
    return f"\\U{code:08x}"


def escape_name(text: str) -> str:
    """``text`` with control and other non-printable characters escaped (``\\x1b``), a
    backslash doubled, and printable Unicode (spaces included) kept."""
    if text.isprintable() and "\\" not in text:
        return text  # the common case costs one scan
    return "".join(_escape_char(char) for char in text)


def escape_names(texts: Iterable[str], separator: str = ", ") -> str:
    """The escaped ``texts`` joined by ``separator`` (for error messages listing names)."""
    return separator.join(escape_name(text) for text in texts)
