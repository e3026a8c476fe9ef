"""Where a model element came from: file and line, with the column found on demand."""

from __future__ import annotations

import itertools
import operator
from typing import NamedTuple

from robomodel.errors import SourceLocation

__all__ = ["SourceSpan", "SourceText"]


class SourceText:
    """The raw text of a parsed document, used to find columns of elements lazily."""

    __slots__ = ("_line_starts", "data", "path")

    def __init__(self, data: bytes, path: str | None) -> None:
        self.data = data
        self.path = path
        self._line_starts: list[int] | None = None

    def _starts(self) -> list[int]:
        if self._line_starts is None:
            # Line i starts after the lengths of lines 0..i-1 plus their i newlines; map and
            # accumulate keep the loop in C (no numpy: checking a URDF should not import it).
            lengths = map(len, self.data.split(b"\n")[:-1])
            ends = itertools.accumulate(lengths, initial=0)
            self._line_starts = list(map(operator.add, ends, itertools.count()))
        return self._line_starts

    def column_of(self, tag: str, line: int, ordinal: int = 0) -> int | None:
        """Return the 1-based column of the ``ordinal``-th ``<tag`` ending on ``line``.

        libxml2 reports the line on which a start tag *ends*; the tag may begin earlier, so
        when the line holds no ``<tag`` the search goes backwards from it.
        """
        starts = self._starts()
        if line < 1 or line > len(starts):
            return None
        begin = starts[line - 1]
        end = starts[line] if line < len(starts) else len(self.data)
        needle = b"<" + tag.encode()
        hits: list[int] = []
        pos = self.data.find(needle, begin, end)
        while pos >= 0:
            nxt = self.data[pos + len(needle) : pos + len(needle) + 1]
            if nxt in (b" ", b"\t", b"\n", b"\r", b"/", b">", b""):
                hits.append(pos)
            pos = self.data.find(needle, pos + 1, end)
        if hits:
            pos = hits[min(ordinal, len(hits) - 1)]
        else:
            pos = self.data.rfind(needle, 0, begin)
            if pos < 0:
                return None
            line_start = self.data.rfind(b"\n", 0, pos) + 1
            return len(self.data[line_start:pos].decode("utf-8", "replace")) + 1
        return len(self.data[begin:pos].decode("utf-8", "replace")) + 1

    def line_of(self, tag: str, line: int) -> int:
        """Return the line on which the ``<tag`` that ends on ``line`` begins."""
        starts = self._starts()
        if line < 1 or line > len(starts):
            return line
        begin = starts[line - 1]
        end = starts[line] if line < len(starts) else len(self.data)
        needle = b"<" + tag.encode()
        if self.data.find(needle, begin, end) >= 0:
            return line
        pos = self.data.rfind(needle, 0, begin)
        return line if pos < 0 else self.data.count(b"\n", 0, pos) + 1


class SourceSpan(NamedTuple):
    """The source position of a model element. Never part of model equality.

    A named tuple rather than a dataclass: one is created per element on every parse, and
    tuple construction is several times cheaper.
    """

    path: str | None
    sourceline: int | None
    tag: str = ""
    ordinal: int = 0
    text: SourceText | None = None

    @property
    def location(self) -> SourceLocation:
        """The ``file:line:column`` where the element's start tag begins."""
        if self.sourceline is None:
            return SourceLocation(self.path, None, None)
        if self.text is None:
            return SourceLocation(self.path, self.sourceline, 1)
        column = self.text.column_of(self.tag, self.sourceline, self.ordinal)
        line = self.text.line_of(self.tag, self.sourceline)
        return SourceLocation(self.path, line, column)

    @property
    def line(self) -> int | None:
        return self.location.line
