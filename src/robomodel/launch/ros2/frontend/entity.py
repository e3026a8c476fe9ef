"""One element of an XML or YAML launch file, with its attributes and children."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from robomodel.errors import SourceLocation

__all__ = ["Entity", "FrontendError"]


class FrontendError(ValueError):
    """A malformed element (bad attribute, missing attribute, unknown tag)."""

    def __init__(self, message: str, location: SourceLocation | None) -> None:
        super().__init__(message)
        self.location = location


@dataclass
class Entity:
    """A tag with attributes; ``children`` are the nested tags in order (XML elements, or the
    YAML ``children`` list), ``lists`` the YAML lists by key (``param``, ``remap``, ``arg``).
    """

    type_name: str
    attrs: dict[str, Any]
    children: list[Entity]
    location: SourceLocation
    lists: dict[str, list[Entity]] = field(default_factory=dict)
    read: set[str] = field(default_factory=set)

    def error(self, message: str) -> FrontendError:
        """A FrontendError at this element."""
        return FrontendError(message, self.location)

    def get(self, name: str, *, optional: bool = True) -> Any:
        """An attribute's raw value (None if absent and optional)."""
        self.read.add(name)
        if name in self.attrs:
            return self.attrs[name]
        if not optional:
            raise self.error(f"<{self.type_name}> requires the attribute '{name}'")
        return None

    def get_bool(self, name: str) -> bool | None:
        """A boolean attribute (``true``/``false``, any case)."""
        value = self.get(name)
        if value is None or isinstance(value, bool):
            return value
        text = str(value).strip().lower()
        if text in ("true", "1"):
            return True
        if text in ("false", "0"):
            return False
        raise self.error(
            f"Attribute '{name}' of Entity '{self.type_name}' expected to be of type 'bool', "
            f"'{value}' can not be converted"
        )

    def entities(self, name: str) -> list[Entity]:
        """Nested entities of one kind (``<param>`` children, YAML ``param:`` list)."""
        self.read.add(name)
        if name in self.lists:
            return self.lists[name]
        return [child for child in self.children if child.type_name == name]

    def check_attributes(self, allowed: tuple[str, ...]) -> None:
        """Fail on an attribute the element does not take (launch's "Unexpected attribute")."""
        unknown = sorted(set(self.attrs) - set(allowed) - {"if", "unless"})
        if unknown:
            raise self.error(
                f"Unexpected attribute(s) found in `{self.type_name}`: {', '.join(unknown)}; "
                f"valid: {', '.join(allowed)}, if, unless"
            )
