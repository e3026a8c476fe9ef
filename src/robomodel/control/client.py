"""A controller manager's services from another node or process (what ros2controlcli and the
spawners call), for robomodel's managers and real ros2_control ones alike."""

from __future__ import annotations

import threading
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Any

from robomodel.runtime.msg.types import controller_manager_msgs as cm_msgs
from robomodel.runtime.msg.types.builtin_interfaces import Duration

if TYPE_CHECKING:
    from robomodel.runtime.context import Context

__all__ = ["NO_DEADLINE_S", "AttemptsClient", "ManagerClient"]

# rospy's ServiceProxy call (ROS 1's spawner and controller_manager scripts) has no deadline;
# a day stands for none, as every transport takes a finite timeout.
NO_DEADLINE_S = 86400.0


class ManagerClient:
    """The services under ``prefix`` (``/<namespace>/controller_manager``).

    Args:
        timeout_s: How long each call may take [s] (``NO_DEADLINE_S``: as rospy, no deadline).
    """

    def __init__(self, context: Context, prefix: str, *, timeout_s: float = 10.0) -> None:
        self.context = context
        self.prefix = "/" + prefix.strip("/")
        self.timeout_s = timeout_s

    def call(
        self, service: str, srv_type: Any, request: Any = None, timeout_s: float | None = None
    ) -> Any:
        return self.context.call_service(
            f"{self.prefix}/{service}",
            srv_type,
            request,
            self.timeout_s if timeout_s is None else timeout_s,
        )

    def list_controllers(self, timeout_s: float | None = None) -> list[cm_msgs.ControllerState]:
        return list(
            self.call("list_controllers", cm_msgs.ListControllers, None, timeout_s).controller
        )

    def list_types(self) -> list[str]:
        return list(self.call("list_controller_types", cm_msgs.ListControllerTypes).types)

    def list_interfaces(self) -> cm_msgs.ListHardwareInterfaces_Response:
        reply: cm_msgs.ListHardwareInterfaces_Response = self.call(
            "list_hardware_interfaces", cm_msgs.ListHardwareInterfaces
        )
        return reply

    def list_components(self) -> list[cm_msgs.HardwareComponentState]:
        return list(self.call("list_hardware_components", cm_msgs.ListHardwareComponents).component)

    def set_controller_parameters(
        self, name: str, *, type_name: str | None = None, params_files: Sequence[str] = ()
    ) -> None:
        """``<name>.type`` and ``<name>.params_file`` on the manager, as the spawner's
        ``--controller-type`` (Humble) and ``--param-file`` (Humble, Jazzy: a list) set them
        before ``load_controller``."""
        from robomodel.runtime.param_client import ParameterClient

        values: dict[str, Any] = {}
        if type_name:
            values[f"{name}.type"] = type_name
        if params_files:
            values[f"{name}.params_file"] = list(params_files)
        if values:
            ParameterClient(self.context, self.prefix, timeout_s=self.timeout_s).set(values)

    def load(self, name: str) -> bool:
        return bool(
            self.call(
                "load_controller", cm_msgs.LoadController, cm_msgs.LoadController_Request(name)
            ).ok
        )

    def configure(self, name: str) -> bool:
        if self.context.transport.name == "ros1":
            return True  # ROS 1's load_controller initialises the controller; no configure
        request = cm_msgs.ConfigureController_Request(name)
        return bool(self.call("configure_controller", cm_msgs.ConfigureController, request).ok)

    def cleanup(self, name: str) -> bool:
        request = cm_msgs.CleanupController_Request(name)
        return bool(self.call("cleanup_controller", cm_msgs.CleanupController, request).ok)

    def unload(self, name: str) -> bool:
        request = cm_msgs.UnloadController_Request(name)
        return bool(self.call("unload_controller", cm_msgs.UnloadController, request).ok)

    def switch(
        self,
        activate: Sequence[str] = (),
        deactivate: Sequence[str] = (),
        strictness: int = cm_msgs.SwitchController_Request.STRICT,
        *,
        timeout_s: float = 0.0,
    ) -> tuple[bool, str]:
        """(ok, message) of ``switch_controller``."""
        request = cm_msgs.SwitchController_Request(
            activate_controllers=list(activate),
            deactivate_controllers=list(deactivate),
            strictness=strictness,
            timeout=Duration.from_seconds(timeout_s),
        )
        reply = self.call("switch_controller", cm_msgs.SwitchController, request)
        return bool(reply.ok), str(reply.message)


class AttemptsClient(ManagerClient):
    """Jazzy's spawner calls (controller_manager_services.py ``service_caller``): each call may
    take ``call_timeout_s``, ``attempts`` times, with a warning after each unanswered attempt.

    rclpy sends the request again at each attempt; here the one request is waited for over
    all attempts' time, since a second ``load_controller`` would be refused as already loaded
    when the first was only slow (a loaded machine), which is the case the attempts are for.
    """

    def __init__(
        self,
        context: Context,
        prefix: str,
        *,
        call_timeout_s: float = 10.0,
        attempts: int = 3,
        warn: Callable[[str], None] = lambda _line: None,
    ) -> None:
        super().__init__(context, prefix, timeout_s=call_timeout_s * attempts)
        self.call_timeout_s = call_timeout_s
        self.attempts = attempts
        self.warn = warn

    def call(
        self, service: str, srv_type: Any, request: Any = None, timeout_s: float | None = None
    ) -> Any:
        answered = threading.Event()
        name = f"{self.prefix}/{service}"

        def watch() -> None:
            for attempt in range(1, self.attempts):
                if answered.wait(self.call_timeout_s):
                    return
                self.warn(
                    f"Failed getting a result from calling {name} in {self.call_timeout_s:g}. "
                    f"(Attempt {attempt} of {self.attempts}.)"
                )

        threading.Thread(target=watch, name=f"attempts {name}", daemon=True).start()
        try:
            return super().call(service, srv_type, request, timeout_s)
        finally:
            answered.set()
