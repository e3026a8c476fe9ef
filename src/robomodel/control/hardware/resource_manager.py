"""The resource manager: all hardware components, their value tables and command claiming."""

from __future__ import annotations

import logging
import math
from collections.abc import Iterable, Sequence

from robomodel.control.hardware.base import HardwareComponent, HardwareState, ReturnType
from robomodel.control.hardware.exceptions import (
    HardwareError,
    InterfaceClaimedError,
    UnknownInterfaceError,
)
from robomodel.control.hardware.interfaces import ValueTable

__all__ = ["ResourceManager"]

log = logging.getLogger("robomodel.control")
# Looked up once: the loop compares against these every cycle for every component.
_OK = ReturnType.OK
_ACTIVE, _INACTIVE = HardwareState.ACTIVE, HardwareState.INACTIVE


class ResourceManager:
    """Owns the hardware components and the shared state/command value tables.

    Command interfaces are claimed exclusively (one controller each); state interfaces are
    shared. Command limits (``min``/``max`` of the URDF ``<ros2_control>`` block, tightened by
    the joint's ``<limit>``) are enforced before every write: a value outside is clamped and
    reported once until it is back inside; a non-finite command is replaced by the last good
    one, with a throttled warning.

    Args:
        components: The hardware, in the order they read and write.
        activate: Configure and activate every component now (ros2_control's default for
            components not listed in ``hardware_components_initial_state``).
    """

    def __init__(self, components: Iterable[HardwareComponent] = (), *, activate: bool = True):
        self.states = ValueTable()
        self.commands = ValueTable()
        self.components: list[HardwareComponent] = []
        self.claimed: dict[str, str] = {}
        self._owner_of_command: dict[str, HardwareComponent] = {}
        self._limited: list[tuple[int, float, float]] = []
        self._guarded: list[int] = []
        self._last_good: list[float] = []
        self._out_of_limits: set[int] = set()
        self._limit_count: dict[int, int] = {}
        self._bad_count: dict[int, int] = {}
        for component in components:
            self.add(component, activate=activate)

    def add(self, component: HardwareComponent, *, activate: bool = True) -> None:
        if any(c.name == component.name for c in self.components):
            raise HardwareError(f"two hardware components are named '{component.name}'")
        for d in component.export_command_interfaces():
            if d.name in self.commands:
                raise HardwareError(
                    f"command interface '{d.name}' is exported by both "
                    f"'{self._owner_of_command[d.name].name}' and '{component.name}'"
                )
        component.bind(self.states, self.commands)
        for d in component.export_command_interfaces():
            self._owner_of_command[d.name] = component
            slot = self.commands.slot(d.name, "command")
            self._guarded.append(slot)
            if math.isfinite(d.min) or math.isfinite(d.max):
                self._limited.append((slot, d.min, d.max))
        self._last_good = list(self.commands.values)
        self.components.append(component)
        if activate:
            component.activate()

    def component(self, name: str) -> HardwareComponent:
        for c in self.components:
            if c.name == name:
                return c
        raise HardwareError(
            f"no hardware component '{name}'; components: "
            + ", ".join(c.name for c in self.components)
        )

    # -- claiming ---------------------------------------------------------------------------
    def command_available(self, name: str) -> bool:
        """Exported by a component that is active (humble: also inactive ones)."""
        owner = self._owner_of_command.get(name)
        return owner is not None and owner.state in (HardwareState.ACTIVE, HardwareState.INACTIVE)

    def check_commands(self, names: Sequence[str], owner: str) -> None:
        """Raise if a command interface does not exist or is claimed by another controller."""
        for name in names:
            if name not in self.commands:
                raise UnknownInterfaceError("command", name, tuple(sorted(self.commands.names)))
            holder = self.claimed.get(name)
            if holder is not None and holder != owner:
                raise InterfaceClaimedError(name, holder)

    def check_states(self, names: Sequence[str]) -> None:
        for name in names:
            if name not in self.states:
                raise UnknownInterfaceError("state", name, tuple(sorted(self.states.names)))

    def claim(self, names: Sequence[str], owner: str) -> None:
        self.check_commands(names, owner)
        for name in names:
            self.claimed[name] = owner

    def release(self, names: Sequence[str], owner: str) -> None:
        for name in names:
            if self.claimed.get(name) == owner:
                del self.claimed[name]

    def prepare_switch(self, start: Sequence[str], stop: Sequence[str]) -> bool:
        return all(
            c.prepare_command_mode_switch(
                [n for n in start if c.has_command(n)], [n for n in stop if c.has_command(n)]
            )
            for c in self.components
        )

    def perform_switch(self, start: Sequence[str], stop: Sequence[str]) -> None:
        for c in self.components:
            c.perform_command_mode_switch(
                [n for n in start if c.has_command(n)], [n for n in stop if c.has_command(n)]
            )

    def components_of(self, names: Iterable[str]) -> set[str]:
        return {self._owner_of_command[n].name for n in names if n in self._owner_of_command}

    # -- the loop ---------------------------------------------------------------------------
    def read(self, time_s: float, period_s: float) -> list[HardwareComponent]:
        """Read every active or inactive component; return those that failed."""
        failed: list[HardwareComponent] = []
        for c in self.components:
            state = c.state
            readable = state is _ACTIVE or state is _INACTIVE
            if readable and c.read(time_s, period_s) is not _OK:
                failed.append(c)
        return failed

    def enforce_command_limits(self) -> None:
        """Hold the last good value of non-finite commands; clamp commands to their limits."""
        values = self.commands.values
        last = self._last_good
        isfinite = math.isfinite
        for slot in self._guarded:
            v = values[slot]
            if isfinite(v):
                last[slot] = v
            elif v != v and last[slot] != last[slot]:
                continue  # never commanded yet: NaN means "no command"
            else:
                self._reject(slot, v)
                values[slot] = last[slot]
        for slot, lo, hi in self._limited:
            v = values[slot]
            if v < lo or v > hi:
                clamped = lo if v < lo else hi
                values[slot] = clamped
                last[slot] = clamped
                if slot not in self._out_of_limits:
                    self._out_of_limits.add(slot)
                    self._warn_limit(slot, v, lo, hi, clamped)
            elif self._out_of_limits and slot in self._out_of_limits:
                self._out_of_limits.discard(slot)

    def _warn_limit(self, slot: int, value: float, lo: float, hi: float, clamped: float) -> None:
        """Warn that a command went out of its limits, throttled per interface.

        A controller saturating at an effort limit goes in and out of it every other cycle:
        the 1st, 2nd, 3rd, 5th, 9th, ... time is reported, with the count (ros2_control's
        limiters throttle theirs too).
        """
        n = self._limit_count.get(slot, 0)
        self._limit_count[slot] = n + 1
        if n & (n - 1) == 0:
            log.warning(
                "command %s = %g is outside its limits [%g, %g]; clamped to %g (%d times)",
                self.commands.names[slot],
                value,
                lo,
                hi,
                clamped,
                n + 1,
            )

    def _reject(self, slot: int, value: float) -> None:
        n = self._bad_count.get(slot, 0)
        self._bad_count[slot] = n + 1
        if n & (n - 1) == 0:  # throttled: the 1st, 2nd, 3rd, 5th, 9th, ... time
            log.warning(
                "command %s = %s is not finite; the last good command %g is held (%d times)",
                self.commands.names[slot],
                value,
                self._last_good[slot],
                n + 1,
            )

    @property
    def out_of_limits(self) -> tuple[str, ...]:
        """Command interfaces clamped on the last write (reported once per episode)."""
        return tuple(self.commands.names[s] for s in sorted(self._out_of_limits))

    def write(self, time_s: float, period_s: float) -> list[HardwareComponent]:
        """Enforce limits, then write every active component; return those that failed."""
        self.enforce_command_limits()
        failed: list[HardwareComponent] = []
        for c in self.components:
            if c.state is _ACTIVE and c.write(time_s, period_s) is not _OK:
                failed.append(c)
        return failed

    # -- introspection ----------------------------------------------------------------------
    def list_interfaces(self) -> dict[str, list[dict[str, object]]]:
        """``list_hardware_interfaces``: command (available, claimed) and state interfaces."""
        return {
            "command": [
                {
                    "name": n,
                    "available": self.command_available(n),
                    "claimed": n in self.claimed,
                }
                for n in sorted(self.commands.names)
            ],
            "state": [{"name": n} for n in sorted(self.states.names)],
        }
