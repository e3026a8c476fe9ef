"""The controller manager's services with their controller_manager_msgs types (Jazzy), under
``<namespace>/<manager>/<service>`` (controller_manager.cpp ``init_services``), so that
``ros2 control list_controllers``, the ros2_control spawner and robomodel's own clients work
alike.

As in ros2_control, a refused request answers ``ok: false`` (SwitchController also says why in
``message``) and the reason is logged by the manager; the manager's process never raises. A
controller's type and parameters file may be set, before ``load_controller``, as the manager's
parameters ``<controller>.type`` and ``<controller>.params_file`` (what the spawner's
``--controller-type`` (Humble) and ``--param-file`` do).
"""

from __future__ import annotations

import logging
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any

from robomodel.control.controllers.registry import CONTROLLER_TYPES
from robomodel.errors import RobomodelError
from robomodel.runtime.msg.types import controller_manager_msgs as cm_msgs
from robomodel.runtime.msg.types.lifecycle_msgs import State

if TYPE_CHECKING:
    from robomodel.control.manager import ControllerManager
    from robomodel.runtime.node import Node

__all__ = ["SERVICES", "lifecycle_state", "register_services"]

log = logging.getLogger("robomodel.control")

_LIFECYCLE = {"unconfigured": 1, "inactive": 2, "active": 3, "finalized": 4}


def lifecycle_state(label: str) -> State:
    """A controller's or component's state as lifecycle_msgs/State (``id``, ``label``)."""
    return State(_LIFECYCLE.get(label, 0), label)


def _guarded(cm: ControllerManager, action: Callable[[], object], what: str) -> str | None:
    """Run ``action``; the reason it failed (also logged, on the manager node's logger, as the
    controller_manager logs it), or None."""
    try:
        action()
    except (RobomodelError, KeyError, ValueError) as exc:
        reason = str(exc)
        (cm.node.logger if cm.node is not None else log).error("%s: %s", what, reason)
        return reason or type(exc).__name__
    return None


def _controller_state(info: dict[str, Any], ros1: bool = False) -> cm_msgs.ControllerState:
    """One controller of ``list_controllers``. On a ROS 1 graph, a controller loaded and never
    started is ``unconfigured``, which the ROS 1 wire says as ROS 1's ``initialized``
    (controller_manager.cpp ``listControllerSrv``: ``isInitialized()`` before ``isStopped()``);
    ROS 1's load initialises it, so robomodel's manager holds it ``inactive``."""
    state = info["state"]
    if ros1 and state == "inactive" and not info.get("started"):
        state = "unconfigured"
    return cm_msgs.ControllerState(
        name=info["name"],
        state=state,
        type=info["type"],
        update_rate=int(info["update_rate"]),
        claimed_interfaces=list(info["claimed_interfaces"]),
        required_command_interfaces=list(info["required_command_interfaces"]),
        required_state_interfaces=list(info["required_state_interfaces"]),
    )


def _interfaces(cm: ControllerManager) -> cm_msgs.ListHardwareInterfaces_Response:
    listed = cm.resources.list_interfaces()
    return cm_msgs.ListHardwareInterfaces_Response(
        command_interfaces=[
            cm_msgs.HardwareInterface(
                str(i["name"]), "double", bool(i["available"]), bool(i["claimed"])
            )
            for i in listed["command"]
        ],
        state_interfaces=[
            cm_msgs.HardwareInterface(str(i["name"]), "double", True, False)
            for i in listed["state"]
        ],
    )


def _components(cm: ControllerManager) -> cm_msgs.ListHardwareComponents_Response:
    resources = cm.resources
    components = []
    for c in resources.components:
        commands = {d.name for d in c.export_command_interfaces()}
        states = [d.name for d in c.export_state_interfaces()]
        components.append(
            cm_msgs.HardwareComponentState(
                name=c.name,
                type=c.info.type,
                plugin_name=c.info.plugin,
                state=lifecycle_state(c.state.value),
                command_interfaces=[
                    cm_msgs.HardwareInterface(
                        n, "double", resources.command_available(n), n in resources.claimed
                    )
                    for n in sorted(commands)
                ],
                state_interfaces=[
                    cm_msgs.HardwareInterface(n, "double", True, False) for n in states
                ],
            )
        )
    return cm_msgs.ListHardwareComponents_Response(components)


def _spec_from_parameters(node: Node | None, name: str) -> tuple[str | None, dict[str, Any] | None]:
    """``<name>.type`` and the parameters of ``<name>.params_file`` set on the manager."""
    if node is None:
        return None, None
    store = node.parameters
    type_name = store.get(f"{name}.type") if store.has(f"{name}.type") else None
    params: dict[str, Any] | None = None
    if store.has(f"{name}.params_file"):
        from robomodel.runtime.param_files import parameters_from_file

        files = store.get(f"{name}.params_file")
        params = {}
        for path in [files] if isinstance(files, str) else list(files):
            fqn = f"{node.namespace.rstrip('/')}/{name}"
            params.update(parameters_from_file(Path(str(path)), fqn))
        if type_name is None and "type" in params:
            type_name = params.pop("type")
        params.pop("type", None)
    return (str(type_name) if type_name is not None else None), params


def _load(
    cm: ControllerManager, request: cm_msgs.LoadController_Request
) -> cm_msgs.LoadController_Response:
    name = request.name
    type_name, params = _spec_from_parameters(cm.node, name)
    failed = _guarded(
        cm,
        lambda: cm.load_controller(name, type_name, params),
        f"Could not load controller '{name}'",
    )
    if failed is None and _ros1_wire(cm):  # ROS 1's loadController initialises it too
        failed = _guarded(
            cm, lambda: cm.configure_controller(name), f"Could not initialize controller '{name}'"
        )
    return cm_msgs.LoadController_Response(failed is None)


def _ros1_wire(cm: ControllerManager) -> bool:
    """Whether the manager's services are on a ROS 1 graph, where ROS 1's controller_manager
    semantics apply (no configure step: load initialises)."""
    node = cm.node
    return node is not None and node.context.transport.name == "ros1"


def _switch(
    cm: ControllerManager, request: cm_msgs.SwitchController_Request
) -> cm_msgs.SwitchController_Response:
    failed = _guarded(
        cm,
        lambda: cm.switch_controllers(
            list(request.activate_controllers),
            list(request.deactivate_controllers),
            int(request.strictness) or 1,
        ),
        "Could not switch controllers",
    )
    return cm_msgs.SwitchController_Response(failed is None, failed or "")


def _reload(
    cm: ControllerManager, request: cm_msgs.ReloadControllerLibraries_Request
) -> cm_msgs.ReloadControllerLibraries_Response:
    """Unload every controller (they must be inactive unless ``force_kill``); robomodel's
    controllers are Python classes, so there is no library to reload."""
    names = list(cm.entries)

    def unload_all() -> None:
        active = [n for n in names if cm.entries[n].controller.state.value == "active"]
        if active and not request.force_kill:
            raise RobomodelError(
                f"controllers are still active: {', '.join(active)} (use force_kill)"
            )
        if active:
            cm.switch_controllers(deactivate=active, strictness=1)
        for n in names:
            cm.unload_controller(n)

    return cm_msgs.ReloadControllerLibraries_Response(
        _guarded(cm, unload_all, "Could not reload") is None
    )


def _types(ros1: bool) -> cm_msgs.ListControllerTypes_Response:
    """The types a controller file may name: on a ROS 1 graph ros_controllers' names (what ROS
    1's ``controller_manager list-types`` prints, base class ``controller_interface::
    ControllerBase``), elsewhere ros2_control's (``controller_interface::ControllerInterface``)."""
    from robomodel.control.config import ROS1_TYPES

    types = sorted(ROS1_TYPES if ros1 else CONTROLLER_TYPES)
    base = "controller_interface::" + ("ControllerBase" if ros1 else "ControllerInterface")
    return cm_msgs.ListControllerTypes_Response(types, [base] * len(types))


def _handlers(
    cm: ControllerManager, ros1: bool = False
) -> list[tuple[str, Any, Callable[[Any], Any]]]:
    m = cm_msgs
    return [
        ("list_controllers", m.ListControllers,
         lambda r: m.ListControllers_Response(
             [_controller_state(i, ros1) for i in cm.list_controllers()])),
        ("list_controller_types", m.ListControllerTypes, lambda r: _types(ros1)),
        ("list_hardware_interfaces", cm_msgs.ListHardwareInterfaces, lambda r: _interfaces(cm)),
        ("list_hardware_components", cm_msgs.ListHardwareComponents, lambda r: _components(cm)),
        ("load_controller", m.LoadController, lambda r: _load(cm, r)),
        ("configure_controller", m.ConfigureController,
         lambda r: m.ConfigureController_Response(
             _guarded(cm, lambda: cm.configure_controller(r.name), f"Could not configure '{r.name}'") is None)),
        ("switch_controller", m.SwitchController, lambda r: _switch(cm, r)),
        ("unload_controller", m.UnloadController,
         lambda r: m.UnloadController_Response(
             _guarded(cm, lambda: cm.unload_controller(r.name), f"Could not unload '{r.name}'") is None)),
        ("cleanup_controller", m.CleanupController,
         lambda r: m.CleanupController_Response(
             _guarded(cm, lambda: cm.cleanup_controller(r.name), f"Could not clean up '{r.name}'") is None)),
        ("reload_controller_libraries", m.ReloadControllerLibraries, lambda r: _reload(cm, r)),
    ]  # fmt: skip


SERVICES = (
    "list_controllers",
    "list_controller_types",
    "list_hardware_interfaces",
    "list_hardware_components",
    "load_controller",
    "configure_controller",
    "switch_controller",
    "unload_controller",
    "cleanup_controller",
    "reload_controller_libraries",
)


def register_services(cm: ControllerManager, node: Node) -> list[Callable[[], None]]:
    """Offer the manager's services on its node; returns the unregister functions."""
    prefix = cm.service_prefix
    handlers = _handlers(cm, ros1=node.context.transport.name == "ros1")
    if node.context.transport.name == "zenoh":  # rmw_zenoh keys a service by its type hash
        handlers += _variant_handlers(cm)
    return [
        node.create_service(srv_type, f"{prefix}/{name}", handler).destroy
        for name, srv_type, handler in handlers
    ]


def _variant_handlers(cm: ControllerManager) -> list[tuple[str, Any, Callable[[Any], Any]]]:
    """list_controllers in the layouts of earlier Jazzy ros2_control releases (each its own
    hash, so an older ``ros2 control list_controllers`` finds the manager too)."""
    from robomodel.runtime.msg.service_variants import (
        LIST_CONTROLLERS_VARIANTS,
        ListControllersVariant,
        downgrade,
    )

    def handler(variant: ListControllersVariant) -> Callable[[Any], Any]:
        response: Any = variant.srv_type.Response  # a dataclass with one field, controller
        return lambda r: response(
            [downgrade(_controller_state(i), variant) for i in cm.list_controllers()]
        )

    return [("list_controllers", v.srv_type, handler(v)) for v in LIST_CONTROLLERS_VARIANTS]
