"""Shared state and helpers of one URDF parse: numbers, vectors, origins, diagnostics.

Numbers follow urdfdom's ``strToDouble`` (a C-locale ``std::stringstream`` that must reach
end of input): leading whitespace is allowed, trailing characters, ``nan`` and ``inf`` are not.
Vectors are split on the space character only, empty pieces skipped, as ``Vector3::init``.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from typing import NoReturn

from lxml import etree

from robomodel.description.model.pose import Origin
from robomodel.description.model.source import SourceSpan, SourceText
from robomodel.errors import Diagnostic, InputError, Severity, SourceLocation

__all__ = ["ElementError", "ParseContext", "Version"]

_NUM = r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?"
# Fast path for the common well-formed 3-vector; anything else takes the exact slow path.
_VEC3_RE = re.compile(f" *({_NUM}) +({_NUM}) +({_NUM}) *\\Z")

Version = tuple[int, int]
_new_tuple = tuple.__new__
_IDENTITY = Origin()


class ElementError(Exception):
    """A problem confined to one element; the caller decides whether it is fatal."""

    def __init__(self, message: str, element: etree._Element | None = None) -> None:
        super().__init__(message)
        self.message = message
        self.element = element


def local_tag(element: etree._Element) -> str:
    """The tag as tinyxml sees it: ``prefix:name`` or ``name`` (namespace URIs ignored)."""
    tag = element.tag
    if not isinstance(tag, str):
        return ""
    if tag[0] != "{":
        return tag
    local = tag.rpartition("}")[2]
    prefix = element.prefix
    return f"{prefix}:{local}" if prefix else local


@dataclass(slots=True)
class ParseContext:
    """Everything one parse needs: the source, the URDF version and collected diagnostics."""

    path: str | None
    text: SourceText
    version: Version = (1, 0)
    diagnostics: list[Diagnostic] = field(default_factory=list)
    _ordinals: dict[tuple[int, str], int] = field(default_factory=dict)
    _vectors: dict[str, tuple[float, ...]] = field(default_factory=dict)
    _numbers: dict[str, float] = field(default_factory=dict)
    _origins: dict[tuple[str | None, str | None], Origin] = field(default_factory=dict)

    # -- locations --------------------------------------------------------------------
    def span(self, element: etree._Element) -> SourceSpan:
        line = element.sourceline
        tag = element.tag
        if tag[0] == "{":
            tag = local_tag(element)
        key = (line, tag)
        ordinals = self._ordinals
        ordinal = ordinals.get(key, 0)
        ordinals[key] = ordinal + 1
        # tuple.__new__ skips NamedTuple's Python-level __new__ (one span per element).
        return _new_tuple(SourceSpan, (self.path, line, tag, ordinal, self.text))

    def location(self, element: etree._Element | None) -> SourceLocation:
        if element is None or element.sourceline is None:
            return SourceLocation(self.path, 1, 1)
        tag = local_tag(element)
        line = element.sourceline
        return SourceLocation(
            self.path, self.text.line_of(tag, line), self.text.column_of(tag, line)
        )

    # -- diagnostics ------------------------------------------------------------------
    def fatal(self, message: str, element: etree._Element | None, code: str = "") -> NoReturn:
        diag = Diagnostic(Severity.ERROR, message, self.location(element), code)
        raise InputError(diag, notes=self.diagnostics)

    def warn(self, message: str, element: etree._Element | None, code: str = "") -> None:
        self.diagnostics.append(Diagnostic(Severity.WARNING, message, self.location(element), code))

    def error(self, message: str, element: etree._Element | None, code: str = "") -> None:
        """A non-fatal error: urdfdom logs ``Error:`` and goes on without the element."""
        self.diagnostics.append(Diagnostic(Severity.ERROR, message, self.location(element), code))

    def at_least(self, major: int, minor: int) -> bool:
        return self.version >= (major, minor)

    # -- numbers ----------------------------------------------------------------------
    def number(self, text: str, what: str, element: etree._Element | None = None) -> float:
        """Parse one number like urdfdom's ``strToDouble``; raise ElementError otherwise.

        ``float()`` accepts a superset of what a C-locale stream reads to the end: refuse
        non-finite values, digit separators, trailing whitespace and non-ASCII digits. A text
        seen before in this document is answered from a cache (robots repeat "0", "1", ...).
        """
        cached = self._numbers.get(text)
        if cached is not None:
            return cached
        try:
            value = float(text)
        except ValueError:
            value = math.nan
        if math.isfinite(value) and "_" not in text and not text[-1].isspace() and text.isascii():
            self._numbers[text] = value
            return value
        raise ElementError(
            f"{what} [{text}] is not a valid number; expected a finite decimal such as 0.5 or 1e-3",
            element,
        )

    def vector(
        self, text: str, element: etree._Element, count: int = 3, what: str = "vector"
    ) -> tuple[float, ...]:
        """Parse ``count`` space-separated numbers (``Vector3::init`` rules)."""
        cached = self._vectors.get(text)
        if cached is not None and len(cached) == count:
            return cached
        if count == 3:
            match = _VEC3_RE.match(text)
            if match:
                x, y, z = float(match[1]), float(match[2]), float(match[3])
                if math.isfinite(x + y + z):
                    self._vectors[text] = (x, y, z)
                    return (x, y, z)
        values = []
        for piece in text.split(" "):
            if not piece:
                continue
            try:
                values.append(self.number(piece, what, element))
            except ElementError:
                raise ElementError(
                    f"Unable to parse component [{piece}] to a double (while parsing a "
                    f"{what} value)",
                    element,
                ) from None
        if len(values) != count:
            raise ElementError(
                f"Parser found {len(values)} elements but {count} expected while parsing "
                f"vector [{text}]",
                element,
            )
        result = tuple(values)
        self._vectors[text] = result
        return result

    def optional_number(
        self, element: etree._Element, attribute: str, what: str | None = None
    ) -> float | None:
        text = element.get(attribute)
        if text is None:
            return None
        return self.number(text, what or attribute, element)

    # -- origin -----------------------------------------------------------------------
    def origin(self, element: etree._Element | None) -> Origin:
        """Parse an ``<origin>`` (``parsePose``); raises ElementError when malformed."""
        if element is None:
            return _IDENTITY
        xyz_text = element.get("xyz")
        rpy_text = element.get("rpy")
        quat_text = element.get("quat_xyzw")
        if quat_text is None:
            # Origins repeat a lot ("0 0 0"); equal frozen values can be shared.
            key = (xyz_text, rpy_text)
            cached = self._origins.get(key)
            if cached is None:
                xyz = (0.0, 0.0, 0.0) if xyz_text is None else self.vector(xyz_text, element)
                rpy = (0.0, 0.0, 0.0) if rpy_text is None else self.vector(rpy_text, element)
                cached = self._origins[key] = Origin(xyz, rpy)  # type: ignore[arg-type]
            return cached
        xyz = (0.0, 0.0, 0.0) if xyz_text is None else self.vector(xyz_text, element)
        rpy = (0.0, 0.0, 0.0) if rpy_text is None else self.vector(rpy_text, element)
        quat: tuple[float, ...] | None = None
        if quat_text is not None:
            if not self.at_least(1, 1):
                self.warn(
                    "Ignoring quat_xyzw attribute requiring URDF version 1.1 since specified "
                    f"version is {self.version[0]}.{self.version[1]}.",
                    element,
                    "version-gated",
                )
            elif rpy_text is not None:
                raise ElementError(
                    "Both rpy and quat_xyzw orientations are defined. Use either one or the other.",
                    element,
                )
            else:
                quat = self.vector(quat_text, element, 4)
        return Origin(xyz, rpy, quat)  # type: ignore[arg-type]
