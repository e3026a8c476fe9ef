"""A display's options: RViz's property table (names, defaults, kinds) and value checks."""

from __future__ import annotations

import enum
import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from types import MappingProxyType
from typing import Any

from robomodel.errors import RobomodelError

__all__ = ["DisplayOptionError", "Option", "OptionKind", "color_rgb"]


class DisplayOptionError(RobomodelError):
    """An option value a display cannot take (the message names the option and what is valid)."""


class OptionKind(enum.Enum):
    """How an option is edited and stored in a config."""

    BOOL = "bool"
    INT = "int"
    FLOAT = "float"
    TEXT = "text"
    CHOICE = "choice"  # one of Option.choices
    COLOR = "color"  # RViz's "255; 0; 0" text
    TOPIC = "topic"  # a topic name; the panel offers the graph's topics of message_types
    MAP = "map"  # a nested map kept as read (Marker's Namespaces: {ns: true})


@dataclass(frozen=True, slots=True)
class Option:
    """One row of a display's property table.

    Attributes:
        name: RViz's property name (``"Topic"``, ``"Queue Size"``, ``"Size (m)"``).
        default: RViz's default value.
        kind: How it is edited and checked.
        choices: The values of a CHOICE option.
        minimum: The least value of an INT or FLOAT option.
        maximum: The greatest value of an INT or FLOAT option.
        help: RViz's description of the property.
    """

    name: str
    default: Any
    kind: OptionKind
    choices: tuple[str, ...] = ()
    minimum: float | None = None
    maximum: float | None = None
    help: str = ""

    def coerce(self, value: Any) -> Any:
        """``value`` as this option stores it.

        Raises:
            DisplayOptionError: it is of the wrong kind or out of range.
        """
        try:
            out = _COERCE[self.kind](value)
        except (TypeError, ValueError):
            raise DisplayOptionError(
                f"option '{self.name}' takes a {self.kind.value} value, not {value!r}"
            ) from None
        if self.kind is OptionKind.CHOICE and self.choices and out not in self.choices:
            raise DisplayOptionError(
                f"option '{self.name}' is one of {', '.join(self.choices)}; not {out!r}"
            )
        if isinstance(out, float | int) and not isinstance(out, bool):
            low, high = self.minimum, self.maximum
            if (low is not None and out < low) or (high is not None and out > high):
                raise DisplayOptionError(
                    f"option '{self.name}' must be in [{low}, {high}], not {out}"
                )
        return out


def _bool(value: Any) -> bool:
    if isinstance(value, str):
        if value.strip().lower() in ("true", "1", "yes", "on"):
            return True
        if value.strip().lower() in ("false", "0", "no", "off"):
            return False
        raise ValueError(value)
    return bool(value)


def _float(value: Any) -> float:
    if isinstance(value, bool):
        raise TypeError(value)
    out = float(value)
    if not math.isfinite(out):
        raise ValueError(value)
    return out


def _int(value: Any) -> int:
    out = _float(value)
    if not out.is_integer():
        raise ValueError(value)
    return int(out)


def _color(value: Any) -> str:
    """RViz's ``"r; g; b"`` (0..255 each) from that text or a 3-sequence."""
    parts = value.replace(",", ";").split(";") if isinstance(value, str) else list(value)
    rgb = [round(float(p)) for p in parts]
    if len(rgb) != 3 or not all(0 <= c <= 255 for c in rgb):
        raise ValueError(value)
    return "; ".join(str(c) for c in rgb)


def _map(value: Any) -> Mapping[str, Any]:
    if value is None:
        return MappingProxyType({})
    if not isinstance(value, Mapping):
        raise TypeError(value)
    return MappingProxyType(dict(value))


_COERCE: dict[OptionKind, Callable[[Any], Any]] = {
    OptionKind.BOOL: _bool,
    OptionKind.INT: _int,
    OptionKind.FLOAT: _float,
    OptionKind.TEXT: lambda v: "" if v is None else str(v),
    OptionKind.CHOICE: str,
    OptionKind.COLOR: _color,
    OptionKind.TOPIC: lambda v: "" if v is None else str(v).strip(),
    OptionKind.MAP: _map,
}


def color_rgb(text: str) -> tuple[int, int, int]:
    """A COLOR option's value as ``(r, g, b)``, 0..255 each."""
    r, g, b = (int(p) for p in text.split(";"))
    return r, g, b
