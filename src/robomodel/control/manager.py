"""The controller manager: controller lifecycle, switching, and the read -> update -> write loop.

Follows ros2_control controller_manager.cpp (see ``docs/control.md``): load -> unconfigured,
configure -> inactive, switch (activate claims command interfaces exclusively), deactivate,
cleanup, unload -> finalized. Switches are applied between cycles (the loop is single-threaded
here, so a switch never races an update). A controller whose ``update`` returns ERROR is
deactivated and its ``fallback_controllers`` are activated STRICTly. Per-controller rates use
humble's rule: a controller at ``rate`` runs when ``counter % (cm_rate / rate) == 0`` with
``period = 1 / rate``.
"""

from __future__ import annotations

import logging
from collections.abc import Callable, Mapping, Sequence
from typing import TYPE_CHECKING, Any

from robomodel.control._entry import ControllerEntry as _Entry
from robomodel.control._entry import (
    Strictness,
    controller_info,
    create_entry,
    required_interfaces,
)
from robomodel.control._switch import activate_entry, deactivate_entry, plan_switch
from robomodel.control.config import ControllerConfig, ControllerSpec
from robomodel.control.controllers.base import (
    ControllerInterface,
    ControllerState,
)
from robomodel.control.exceptions import (
    ConfigError,
    ControlError,
    ControllerStateError,
    UnknownControllerError,
)
from robomodel.control.hardware.base import ReturnType
from robomodel.control.hardware.resource_manager import ResourceManager
from robomodel.errors import RobomodelError

if TYPE_CHECKING:
    from robomodel.description.model import Robot
    from robomodel.runtime.context import Context
    from robomodel.runtime.executor import Timer
    from robomodel.runtime.node import Node

__all__ = ["ControllerManager", "Strictness"]

log = logging.getLogger("robomodel.control")

_OK = ReturnType.OK


class ControllerManager:
    """Runs controllers on the hardware of a :class:`ResourceManager`.

    Args:
        resources: The hardware and its interfaces.
        context: Where controller nodes (topics) and the manager's services live; ``None`` runs
            without any bus (pure stepping, e.g. the benchmark).
        robot: The description, given to controllers (joint limits, dynamics).
        update_rate_hz: The loop rate (ros2_control ``update_rate``, default 100).
        name: The manager's node name; services are ``/<namespace>/<name>/list_controllers``...
        namespace: The namespace of the manager and its controllers.
        parameters: The manager node's parameters (``use_sim_time``, ...) from the YAML.
        serve: Offer the services now; False: once :meth:`serve` is called, after the
            configuration is set (a spawner calling ``load_controller`` in between would find
            no controller types).
    """

    def __init__(
        self,
        resources: ResourceManager,
        *,
        context: Context | None = None,
        robot: Robot | None = None,
        update_rate_hz: int = 100,
        name: str = "controller_manager",
        namespace: str = "/",
        parameters: Mapping[str, Any] | None = None,
        serve: bool = True,
    ) -> None:
        if update_rate_hz <= 0:
            raise ControlError(f"update_rate must be positive, got {update_rate_hz}")
        self.resources = resources
        self.context = context
        self.robot = robot
        self.update_rate_hz = int(update_rate_hz)
        self.name = name
        self.namespace = namespace
        self.entries: dict[str, _Entry] = {}
        self.specs: dict[str, ControllerSpec] = {}
        self.spec_source: Callable[[str], ControllerSpec | None] | None = None
        self._active: list[_Entry] = []
        self._run: list[tuple[Callable[[float, float], ReturnType], int, _Entry]] = []
        self._counter = 0
        self.time_s = 0.0
        self._timer: Timer | None = None
        self._unregister: list[Callable[[], None]] = []
        self.node: Node | None = None
        if context is not None:
            params = dict(parameters or {})
            params["update_rate"] = self.update_rate_hz
            self.node = context.create_node(
                name, namespace, parameters=params, allow_undeclared_parameters=True
            )
            if serve:
                self.serve()

    # -- configuration ------------------------------------------------------------------------
    def set_config(self, config: ControllerConfig) -> None:
        """Make the controllers of ``config`` loadable by name (its ``type`` and parameters)."""
        for spec in config.controllers:
            self.specs[spec.name] = spec

    @property
    def service_prefix(self) -> str:
        ns = self.namespace.rstrip("/")
        return f"{ns}/{self.name}"

    # -- lifecycle ------------------------------------------------------------------------------
    def _entry(self, name: str) -> _Entry:
        try:
            return self.entries[name]
        except KeyError:
            raise UnknownControllerError(name, tuple(self.entries)) from None

    def load_controller(
        self, name: str, type_name: str | None = None, params: Mapping[str, Any] | None = None
    ) -> ControllerInterface:
        """Create controller ``name`` (state unconfigured); type and parameters default to
        those of the configuration (:meth:`set_config`), else to what :attr:`spec_source` finds
        (a ROS 1 launch: the parameter server's ``<namespace>/<name>``)."""
        if name in self.entries:
            raise ControlError(f"a controller named '{name}' is already loaded")
        spec = self.specs.get(name)
        if spec is None and type_name is None and self.spec_source is not None:
            spec = self.spec_source(name)
            if spec is not None:
                self.specs[name] = spec
        if type_name is None:
            if spec is None:
                raise ControlError(
                    f"controller '{name}' has no type: it is not in the controller configuration "
                    f"({', '.join(self.specs) or 'none loaded'}) and no type was given"
                )
            type_name = spec.type
        merged: dict[str, Any] = dict(spec.params) if spec is not None else {}
        merged.update(params or {})
        try:
            entry = create_entry(
                name,
                type_name,
                merged,
                context=self.context,
                namespace=self.namespace,
                robot=self.robot,
                manager_rate_hz=self.update_rate_hz,
            )
        except RobomodelError as exc:
            raise self._located(name, exc) from None
        if spec is not None and type_name == spec.type:
            # list_controllers shows the type the file names, as ROS 1's manager lists
            # joint_state_controller/JointStateController
            entry.listed_type = spec.original_type
        self.entries[name] = entry
        return entry.controller

    def _located(self, name: str, exc: RobomodelError) -> RobomodelError:
        """``exc`` with the file:line of the controller's entry in the YAML, when known."""
        spec = self.specs.get(name)
        if spec is None or spec.location is None or isinstance(exc, ConfigError):
            return exc
        return ConfigError(str(exc), spec.location)

    def configure_controller(self, name: str) -> None:
        entry = self._entry(name)
        c = entry.controller
        if c.state is ControllerState.ACTIVE or c.state is ControllerState.FINALIZED:
            raise ControllerStateError(
                f"controller '{name}' is {c.state.value}; only unconfigured or inactive "
                "controllers can be configured (deactivate it first)"
            )
        if c.state is ControllerState.INACTIVE:
            self.cleanup_controller(name)
        c.on_configure()
        c.state = ControllerState.INACTIVE

    def cleanup_controller(self, name: str) -> None:
        c = self._entry(name).controller
        if c.state is ControllerState.UNCONFIGURED:
            return
        if c.state is not ControllerState.INACTIVE:
            raise ControllerStateError(
                f"controller '{name}' is {c.state.value}; only inactive controllers can be cleaned up"
            )
        c.on_cleanup()
        c.state = ControllerState.UNCONFIGURED

    def unload_controller(self, name: str) -> None:
        entry = self._entry(name)
        c = entry.controller
        if c.state is ControllerState.ACTIVE:
            raise ControllerStateError(
                f"controller '{name}' is active; deactivate it before unloading"
            )
        self.cleanup_controller(name)
        c.state = ControllerState.FINALIZED
        if entry.node is not None:
            entry.node.destroy()
        del self.entries[name]

    # -- switching ----------------------------------------------------------------------------
    def required_interfaces(self, name: str) -> tuple[list[str], list[str]]:
        """The full names of the command and state interfaces controller ``name`` needs."""
        return self._interfaces(self._entry(name))

    def _interfaces(self, entry: _Entry) -> tuple[list[str], list[str]]:
        return required_interfaces(entry.controller, self.resources)

    def switch_controllers(
        self,
        activate: Sequence[str] = (),
        deactivate: Sequence[str] = (),
        strictness: Strictness | int = Strictness.STRICT,
    ) -> None:
        """Deactivate then activate controllers (controller_manager ``switch_controller``).

        STRICT: any unknown name, wrong state or unavailable/claimed interface fails the whole
        request (nothing changes). BEST_EFFORT: such entries are dropped.

        Raises:
            ControlError: the request fails (STRICT).
        """
        strict = int(strictness) != int(Strictness.BEST_EFFORT)
        to_activate, to_deactivate = plan_switch(self, activate, deactivate, strict=strict)
        start = [i for n in to_activate for i in self._interfaces(self.entries[n])[0]]
        stop = [i for n in to_deactivate for i in self.entries[n].claimed]
        if not self.resources.prepare_switch(start, stop):
            raise ControlError("switch refused by the hardware (prepare_command_mode_switch)")
        self.resources.perform_switch(start, stop)
        for name in to_deactivate:
            deactivate_entry(self.entries[name], self.resources)
        activated: list[str] = []
        for name in to_activate:
            try:
                activate_entry(self.entries[name], self.resources)
                activated.append(name)
            except RobomodelError as exc:
                if strict:
                    for done in activated:
                        deactivate_entry(self.entries[done], self.resources)
                    raise ControlError(f"activating '{name}' failed: {exc}") from exc
                log.warning("activating '%s' failed: %s", name, exc)
        self._rebuild()

    def _rebuild(self) -> None:
        self._active = [
            e for e in self.entries.values() if e.controller.state is ControllerState.ACTIVE
        ]
        for entry in self._active:  # ROS 1 lists a loaded, never started one as initialized
            entry.extra["started"] = True
        self._run = [(e.controller.update, e.factor, e) for e in self._active]

    # -- spawner --------------------------------------------------------------------------------
    def spawn(self, names: Sequence[str], *, activate: bool = True) -> None:
        """spawner.py: load (if needed), configure and activate each controller (STRICT)."""
        for name in names:
            if name not in self.entries:
                self.load_controller(name)
            if self.entries[name].controller.state is ControllerState.UNCONFIGURED:
                self.configure_controller(name)
            if activate and self.entries[name].controller.state is not ControllerState.ACTIVE:
                self.switch_controllers(activate=[name], strictness=Strictness.STRICT)

    # -- the loop -------------------------------------------------------------------------------
    def read(self, time_s: float, period_s: float) -> None:
        failed = self.resources.read(time_s, period_s)
        if failed:
            self._hardware_failed(failed, "read")

    def update(self, time_s: float, period_s: float) -> None:
        self._counter += 1
        counter = self._counter
        cm_rate = self.update_rate_hz
        errors: list[_Entry] | None = None
        for fn, factor, entry in self._run:
            if factor == 1:
                result = fn(time_s, period_s)
            elif (counter % cm_rate) % factor == 0:  # humble controller_manager.cpp update()
                result = fn(time_s, factor * period_s)
            else:
                continue
            if result is not _OK:
                if errors is None:
                    errors = []
                errors.append(entry)
        if errors:
            self._controllers_failed(errors)

    def write(self, time_s: float, period_s: float) -> None:
        failed = self.resources.write(time_s, period_s)
        if failed:
            self._hardware_failed(failed, "write")

    def step(self, period_s: float | None = None) -> None:
        """One read -> update -> write cycle, advancing the manager's own time by ``period_s``
        (default ``1 / update_rate``)."""
        dt = 1.0 / self.update_rate_hz if period_s is None else period_s
        self.time_s += dt
        t = self.time_s
        self.read(t, dt)
        self.update(t, dt)
        self.write(t, dt)

    def _controllers_failed(self, errors: list[_Entry]) -> None:
        fallbacks: list[str] = []
        for entry in errors:
            log.error("controller '%s' returned ERROR from update(); deactivating it", entry.name)
            deactivate_entry(entry, self.resources)
            fallbacks.extend(f for f in entry.fallback if f not in fallbacks)
        self._rebuild()
        if fallbacks:
            try:
                self.switch_controllers(activate=fallbacks, strictness=Strictness.STRICT)
            except RobomodelError as exc:
                log.error("fallback controllers %s could not be activated: %s", fallbacks, exc)

    def _hardware_failed(self, components: list[Any], what: str) -> None:
        names = {c.name for c in components}
        for entry in list(self._active):
            if self.resources.components_of(entry.claimed) & names:
                log.error("hardware %s failed in %s(); deactivating '%s'", names, what, entry.name)
                deactivate_entry(entry, self.resources)
        self._rebuild()

    # -- real time ------------------------------------------------------------------------------
    def start(self) -> None:
        """Run the loop on a timer of the context at ``update_rate`` (wall or sim clock).

        ``time`` is the clock's time; ``period`` is always the nominal ``1 / update_rate``, even
        after a missed tick (ros2_control passes the measured period; a Python timer jitters and
        misses ticks when the machine is busy, and a long period would make PID loops and the
        mock's effort integration unstable: an overloaded loop runs slower than real time
        instead, like a simulator with a real-time factor below 1).
        """
        if self.node is None:
            raise ControlError("start() needs a controller manager created with a context")
        clock = self.node.get_clock()
        period = 1.0 / self.update_rate_hz

        def cycle() -> None:
            now = clock.now_ns() * 1e-9
            self.time_s = now
            self.read(now, period)
            self.update(now, period)
            self.write(now, period)

        self._timer = self.node.create_timer(period, cycle)

    def stop(self) -> None:
        if self._timer is not None:
            self._timer.cancel()
            self._timer = None

    # -- introspection and services -----------------------------------------------------------
    def list_controllers(self) -> list[dict[str, Any]]:
        """``list_controllers``: name, type, state, update rate and interfaces of each."""
        return [controller_info(e, self.resources) for e in self.entries.values()]

    def serve(self) -> None:
        """Offer the manager's services on its node (once; nothing without a bus)."""
        from robomodel.control.services import register_services

        if self.node is not None and not self._unregister:
            self._unregister.extend(register_services(self, self.node))

    def shutdown(self) -> None:
        self.stop()
        for unregister in self._unregister:
            unregister()
        self._unregister.clear()
        for entry in list(self.entries.values()):
            if entry.controller.state is ControllerState.ACTIVE:
                deactivate_entry(entry, self.resources)
        self._rebuild()

    def close(self) -> None:
        """:meth:`shutdown`, then remove every controller's node and the manager's own (the
        manager's process ending; a new manager of the same name can then start)."""
        self.shutdown()
        for entry in self.entries.values():
            if entry.node is not None:
                entry.node.destroy()
        self.entries.clear()
        self._rebuild()
        if self.node is not None:
            self.node.destroy()
            self.node = None
