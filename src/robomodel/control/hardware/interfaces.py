"""State and command interfaces: names, descriptions and the shared table of values.

Every interface's value lives in one slot of a :class:`ValueTable` (a plain Python list), so a
controller resolves its interfaces to slot numbers once, at activation, and the loop then only
indexes lists: no dictionary lookups by name and no allocation per cycle.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from robomodel.control.hardware.exceptions import UnknownInterfaceError

__all__ = [
    "ACCELERATION",
    "EFFORT",
    "POSITION",
    "VELOCITY",
    "InterfaceDescription",
    "LoanedInterface",
    "ValueTable",
    "default_value",
]

POSITION = "position"
VELOCITY = "velocity"
ACCELERATION = "acceleration"
EFFORT = "effort"

# Initial values by data type (ros2_control hardware_interface_types_userdoc.rst).
_DEFAULTS = {
    "double": math.nan,
    "float32": math.nan,
    "bool": 0.0,
    "uint8": 255.0,
    "int8": 127.0,
    "uint16": 65535.0,
    "int16": 32767.0,
    "uint32": 4294967295.0,
    "int32": 2147483647.0,
}


def default_value(data_type: str) -> float:
    """The value an interface of ``data_type`` holds before anything writes it."""
    return _DEFAULTS.get(data_type, math.nan)


@dataclass(frozen=True, slots=True)
class InterfaceDescription:
    """One interface of one component: ``prefix/interface`` (``joint1/position``).

    Attributes:
        prefix: The joint, sensor or GPIO name.
        interface: ``position``, ``velocity``, ``effort``, ``force.x``, ...
        data_type: ``double`` unless the URDF says otherwise.
        initial_value: From ``<param name="initial_value">``; ``None`` when not given.
        min, max: From ``<param name="min|max">`` (command interfaces); infinite when absent.
    """

    prefix: str
    interface: str
    data_type: str = "double"
    initial_value: float | None = None
    min: float = -math.inf
    max: float = math.inf

    @property
    def name(self) -> str:
        return f"{self.prefix}/{self.interface}"


class ValueTable:
    """Named float slots (one table for states, one for commands)."""

    __slots__ = ("index", "names", "values")

    def __init__(self) -> None:
        self.values: list[float] = []
        self.names: list[str] = []
        self.index: dict[str, int] = {}

    def add(self, name: str, value: float) -> int:
        """Add a slot and return its number (an existing name keeps its slot)."""
        slot = self.index.get(name)
        if slot is not None:
            return slot
        slot = len(self.values)
        self.values.append(value)
        self.names.append(name)
        self.index[name] = slot
        return slot

    def slot(self, name: str, kind: str = "state") -> int:
        try:
            return self.index[name]
        except KeyError:
            raise UnknownInterfaceError(kind, name, tuple(sorted(self.names))) from None

    def __contains__(self, name: object) -> bool:
        return name in self.index

    def __len__(self) -> int:
        return len(self.values)


class LoanedInterface:
    """A controller's handle on one interface (``get``/``set`` by slot, not by name)."""

    __slots__ = ("_values", "name", "slot")

    def __init__(self, table: ValueTable, name: str, kind: str = "state") -> None:
        self.name = name
        self.slot = table.slot(name, kind)
        self._values = table.values

    @property
    def table(self) -> list[float]:
        """The whole value table this interface lives in (index it with :attr:`slot`)."""
        return self._values

    @property
    def prefix(self) -> str:
        return self.name.rpartition("/")[0]

    @property
    def interface(self) -> str:
        return self.name.rpartition("/")[2]

    def get(self) -> float:
        return self._values[self.slot]

    def set(self, value: float) -> None:
        self._values[self.slot] = value
