"""Switching controllers: checking a request (controller_manager.cpp ``switch_controller_cb``)
before applying it, and activating or deactivating one controller."""

from __future__ import annotations

import logging
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

from robomodel.control._entry import ControllerEntry, required_interfaces
from robomodel.control.controllers.base import ControllerState
from robomodel.control.exceptions import ControlError, UnknownControllerError
from robomodel.control.hardware.interfaces import LoanedInterface
from robomodel.errors import RobomodelError

if TYPE_CHECKING:
    from robomodel.control.hardware.resource_manager import ResourceManager
    from robomodel.control.manager import ControllerManager

__all__ = ["activate_entry", "deactivate_entry", "plan_switch"]

log = logging.getLogger("robomodel.control")


@dataclass(frozen=True, slots=True)
class _Refuse:
    """What to do with a problem in a switch request: raise (STRICT) or warn (BEST_EFFORT)."""

    strict: bool

    def __call__(self, message: str) -> None:
        if self.strict:
            raise ControlError(f"switch refused: {message}")
        log.warning("switch: %s; ignored (best effort)", message)


def _deactivations(
    entries: Mapping[str, ControllerEntry], deactivate: Sequence[str], refuse: _Refuse
) -> list[str]:
    """The requested deactivations of known, active controllers."""
    to_deactivate: list[str] = []
    for name in deactivate:
        if name not in entries:
            refuse(str(UnknownControllerError(name, tuple(entries))))
        elif entries[name].controller.state is not ControllerState.ACTIVE:
            refuse(f"controller '{name}' is not active")
        else:
            to_deactivate.append(name)
    return to_deactivate


def _activations(
    entries: Mapping[str, ControllerEntry],
    activate: Sequence[str],
    to_deactivate: Sequence[str],
    refuse: _Refuse,
) -> list[str]:
    """The requested activations of known controllers in a state that can become active (an
    active one only if the same request deactivates it: a restart)."""
    to_activate: list[str] = []
    for name in activate:
        if name not in entries:
            refuse(str(UnknownControllerError(name, tuple(entries))))
            continue
        state = entries[name].controller.state
        if state is ControllerState.ACTIVE and name not in to_deactivate:
            refuse(f"controller '{name}' is already active")
        elif state is ControllerState.UNCONFIGURED:
            refuse(f"controller '{name}' is unconfigured; configure it first")
        elif state is ControllerState.FINALIZED:
            refuse(f"controller '{name}' is finalized")
        else:
            to_activate.append(name)
    return to_activate


def _with_interfaces(
    cm: ControllerManager, to_activate: list[str], to_deactivate: Sequence[str], refuse: _Refuse
) -> list[str]:
    """The activations whose interfaces are available, counting what the deactivations
    release, and that claim no command interface another activation of the request claims."""
    resources = cm.resources
    releasing = {i for n in to_deactivate for i in cm.entries[n].claimed}
    taken: dict[str, str] = {}
    kept = list(to_activate)
    for name in to_activate:
        commands, states = cm.required_interfaces(name)
        try:
            resources.check_states(states)
            for iface in commands:
                holder = resources.claimed.get(iface)
                if holder is not None and iface not in releasing:
                    resources.check_commands([iface], name)
                if iface in taken:
                    raise ControlError(
                        f"controllers '{taken[iface]}' and '{name}' both claim '{iface}'"
                    )
            resources.check_commands([i for i in commands if i not in resources.claimed], name)
        except RobomodelError as exc:
            refuse(f"cannot activate '{name}': {exc}")
            kept.remove(name)
            continue
        # only a kept activation claims: one dropped (best effort) reserves nothing
        taken.update(dict.fromkeys(commands, name))
    return kept


def plan_switch(
    cm: ControllerManager,
    activate: Sequence[str],
    deactivate: Sequence[str],
    *,
    strict: bool,
) -> tuple[list[str], list[str]]:
    """The controllers to activate and to deactivate after checking the request.

    STRICT raises :class:`ControlError` on the first problem (nothing has changed yet);
    BEST_EFFORT drops the offending entry with a warning. Problems: unknown names, a controller
    in the wrong state (activating one that is active, unconfigured or finalized; deactivating
    one that is not active), a missing state or command interface, a command interface claimed
    by a controller that stays active, or two controllers of the request claiming one interface.
    """
    refuse = _Refuse(strict)
    to_deactivate = _deactivations(cm.entries, deactivate, refuse)
    to_activate = _activations(cm.entries, activate, to_deactivate, refuse)
    return _with_interfaces(cm, to_activate, to_deactivate, refuse), to_deactivate


def activate_entry(entry: ControllerEntry, rm: ResourceManager) -> None:
    """Claim ``entry``'s command interfaces, loan them and its state interfaces to the
    controller and activate it; on failure nothing stays claimed or loaned."""
    commands, states = required_interfaces(entry.controller, rm)
    rm.claim(commands, entry.name)
    try:
        loaned_cmd = [LoanedInterface(rm.commands, n, "command") for n in commands]
        loaned_st = [LoanedInterface(rm.states, n, "state") for n in states]
        entry.controller.assign_interfaces(loaned_cmd, loaned_st)
        entry.controller.on_activate()
    except Exception:
        rm.release(commands, entry.name)
        entry.controller.release_interfaces()
        raise
    entry.claimed = tuple(commands)
    entry.state_names = tuple(states)
    entry.controller.state = ControllerState.ACTIVE


def deactivate_entry(entry: ControllerEntry, rm: ResourceManager) -> None:
    """Deactivate ``entry``'s controller and release its interfaces (even if
    ``on_deactivate`` raises)."""
    try:
        entry.controller.on_deactivate()
    finally:
        rm.release(entry.claimed, entry.name)
        entry.claimed = ()
        entry.controller.release_interfaces()
        entry.controller.state = ControllerState.INACTIVE
