"""Generated Python source, line by line: what the CDR codecs (``_cdr_codegen.Gen``) and the ROS 1
codec (``transport/ros1/ros1_codec.py``) both build their encoders and decoders with."""

from __future__ import annotations

from typing import Any

__all__ = ["SourceGen"]


class SourceGen:
    """Accumulates generated source lines and the objects they refer to by name (``env``, the
    globals the source is ``exec``-ed in)."""

    def __init__(self, env: dict[str, Any]) -> None:
        self.lines: list[str] = []
        self.env: dict[str, Any] = dict(env)
        self._n = 0

    def name(self, prefix: str) -> str:
        """A fresh variable name: ``prefix`` and a number."""
        self._n += 1
        return f"{prefix}{self._n}"

    def ref(self, obj: Any, prefix: str) -> str:
        """A fresh global name bound to ``obj``."""
        name = self.name(prefix)
        self.env[name] = obj
        return name

    def emit(self, depth: int, line: str) -> None:
        self.lines.append("    " * depth + line)
