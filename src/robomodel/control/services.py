"""The controller manager's services on the bus (controller_manager.cpp ``init_services``).

Each is ``<namespace>/<manager>/<service>`` with a JSON-like request and response; failures
answer ``{"ok": false, "error": "..."}`` rather than raising in the manager's process.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from robomodel.control.controllers.registry import CONTROLLER_TYPES
from robomodel.errors import RobomodelError

if TYPE_CHECKING:
    from robomodel.control.manager import ControllerManager
    from robomodel.runtime.context import Context

__all__ = ["SERVICES", "register_services"]

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
)

Handler = Callable[[dict[str, Any]], dict[str, Any]]


def _guarded(action: Callable[[], None]) -> dict[str, Any]:
    try:
        action()
    except (RobomodelError, KeyError) as exc:
        return {"ok": False, "error": str(exc)}
    return {"ok": True}


def _handlers(cm: ControllerManager) -> dict[str, Handler]:
    def load(request: dict[str, Any]) -> dict[str, Any]:
        name = str(request["name"])

        def run() -> None:
            params = request.get("params")
            cm.load_controller(
                name, request.get("type"), params if isinstance(params, dict) else None
            )
            target = request.get("set_state")
            if target in ("inactive", "active"):
                cm.configure_controller(name)
            if target == "active":
                cm.switch_controllers(activate=[name])

        return _guarded(run)

    def components(_: dict[str, Any]) -> dict[str, Any]:
        return {
            "components": [
                {
                    "name": c.name,
                    "type": c.info.type,
                    "plugin": c.info.plugin,
                    "state": c.state.value,
                }
                for c in cm.resources.components
            ]
        }

    return {
        "list_controllers": lambda r: {"controllers": cm.list_controllers()},
        "list_controller_types": lambda r: {"types": sorted(CONTROLLER_TYPES)},
        "list_hardware_interfaces": lambda r: cm.resources.list_interfaces(),
        "list_hardware_components": components,
        "load_controller": load,
        "configure_controller": lambda r: _guarded(lambda: cm.configure_controller(r["name"])),
        "switch_controller": lambda r: _guarded(
            lambda: cm.switch_controllers(
                r.get("activate", []), r.get("deactivate", []), int(r.get("strictness", 2))
            )
        ),
        "unload_controller": lambda r: _guarded(lambda: cm.unload_controller(r["name"])),
        "cleanup_controller": lambda r: _guarded(lambda: cm.cleanup_controller(r["name"])),
    }


def register_services(cm: ControllerManager, context: Context) -> list[Callable[[], None]]:
    """Offer the manager's services; returns the unregister functions."""
    prefix = cm.service_prefix
    return [
        context.create_service(f"{prefix}/{name}", handler)
        for name, handler in _handlers(cm).items()
    ]
