"""Elements robomodel does not interpret, kept verbatim so that nothing is lost on a round trip."""

from __future__ import annotations

from dataclasses import dataclass, field

from robomodel.description.model.source import SourceSpan

__all__ = ["RawElement"]


@dataclass(frozen=True, slots=True)
class RawElement:
    """An XML element kept as serialized text (``xml``), with its tag for quick filtering."""

    tag: str
    xml: str
    span: SourceSpan | None = field(default=None, compare=False, repr=False)
