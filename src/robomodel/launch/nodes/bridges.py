"""The WebSocket bridges as nodes: rosbridge_server's ``rosbridge_websocket`` and
foxglove_bridge's ``foxglove_bridge``.

Parameters as the real node takes them (ROS 1 ``~port``, ROS 2 ``port``): ``port`` (9090),
``address`` (loopback here, where rosbridge listens on every interface: say ``0.0.0.0`` to be
reached from other machines), ``max_message_size`` (the largest frame a client may send
[bytes]) and ``send_buffer_limit`` (the bytes waiting for one client before the oldest are
dropped, foxglove_bridge's name). rosapi's services are the bridge's own
(:mod:`robomodel.bridges.rosapi`).

foxglove_bridge's node takes foxglove_bridge's parameters: ``port`` (8765), ``address``, the
whitelists ``topic_whitelist``, ``param_whitelist``, ``service_whitelist``,
``client_topic_whitelist`` and ``asset_uri_allowlist``, ``send_buffer_limit``,
``max_qos_depth``, ``capabilities`` and ``use_sim_time`` (ROS 1: the global ``/use_sim_time``).
"""

from __future__ import annotations

from typing import Any

from robomodel.errors import RobomodelError
from robomodel.launch.nodes.base import NodeContext, RunningNode, register

__all__: list[str] = []


class _BridgeNode:
    """A started bridge: it runs until stopped."""

    def __init__(self, server: Any) -> None:
        self.server = server
        self._code: int | None = None

    def stop(self) -> None:
        if self._code is None:
            self._code = 0
            self.server.stop()

    def exit_code(self) -> int | None:
        return self._code


def _number(value: Any, name: str, fqn: str, *, low: int, high: int) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or not low <= value <= high:
        raise RobomodelError(
            f"{fqn}: parameter {name} must be a whole number in [{low}, {high}], got {value!r}"
        )
    return value


def _start(ctx: NodeContext, settings: dict[str, Any], params: Any, name: str) -> RunningNode:
    from robomodel.bridges import BridgeLimits
    from robomodel.bridges.rosbridge import RosbridgeServer

    fqn = ctx.spec.fqn
    port = _number(settings.get("port", 9090), "port", fqn, low=0, high=65535)
    address = settings.get("address", "127.0.0.1")
    if not isinstance(address, str):
        raise RobomodelError(f"{fqn}: parameter address must be a host name or address")
    defaults = BridgeLimits()
    limits = BridgeLimits(
        max_frame_bytes=_number(settings.get("max_message_size", defaults.max_frame_bytes),
                                "max_message_size", fqn, low=1024, high=2**31),
        send_buffer_bytes=_number(settings.get("send_buffer_limit", defaults.send_buffer_bytes),
                                  "send_buffer_limit", fqn, low=1024, high=2**31),
    )  # fmt: skip
    server = RosbridgeServer(
        ctx.runtime,
        params,
        dialect=ctx.spec.dialect,
        name=name,
        namespace=ctx.namespace,
        address=address or "127.0.0.1",
        port=port,
        limits=limits,
        log=ctx.log,
    )
    return _BridgeNode(server)


_SETTINGS = ("port", "address", "max_message_size", "send_buffer_limit")


@register("ros1", "rosbridge_server", "rosbridge_websocket", "rosbridge_websocket.py",
          purpose="rosbridge v2 JSON over a WebSocket (port 9090), with rosapi")  # fmt: skip
def rosbridge_websocket_ros1(ctx: NodeContext) -> RunningNode:
    from robomodel.bridges.rosapi import Ros1Params

    settings = {k: ctx.param(f"~{k}") for k in _SETTINGS if ctx.param(f"~{k}") is not None}
    name = ctx.spec.name or "rosbridge_websocket"
    return _start(ctx, settings, Ros1Params(ctx.params), name)


@register("ros2", "rosbridge_server", "rosbridge_websocket",
          purpose="rosbridge v2 JSON over a WebSocket (port 9090), with rosapi")  # fmt: skip
def rosbridge_websocket_ros2(ctx: NodeContext) -> RunningNode:
    from robomodel.bridges.rosapi import Ros2Params

    name = ctx.spec.name or "rosbridge_websocket"
    settings = {k: v for k, v in ctx.ros2_parameters(name).items() if k in _SETTINGS}
    runtime = ctx.runtime
    params = Ros2Params(runtime, lambda: sorted(runtime.graph(timeout_s=0.3).nodes), 1.0)
    return _start(ctx, settings, params, name)


_FOXGLOVE = ("port", "address", "topic_whitelist", "param_whitelist", "service_whitelist",
             "client_topic_whitelist", "asset_uri_allowlist", "send_buffer_limit",
             "max_qos_depth", "capabilities", "use_sim_time")  # fmt: skip


def _strings(value: Any, name: str, fqn: str) -> tuple[str, ...]:
    if isinstance(value, str):
        return (value,)
    if not isinstance(value, list | tuple) or not all(isinstance(v, str) for v in value):
        raise RobomodelError(f"{fqn}: parameter {name} must be a list of strings, got {value!r}")
    return tuple(value)


def _flag(value: Any, name: str, fqn: str) -> bool:
    if isinstance(value, str) and value.lower() in ("true", "false"):
        return value.lower() == "true"
    if not isinstance(value, bool):
        raise RobomodelError(f"{fqn}: parameter {name} must be true or false, got {value!r}")
    return value


def _start_foxglove(
    ctx: NodeContext, settings: dict[str, Any], params: Any, name: str
) -> RunningNode:
    from robomodel.bridges.foxglove_bridge import (
        CAPABILITIES,
        DEFAULT_ASSET_ALLOWLIST,
        FoxgloveBridge,
    )

    fqn = ctx.spec.fqn
    address = settings.get("address", "127.0.0.1")
    if not isinstance(address, str):
        raise RobomodelError(f"{fqn}: parameter address must be a host name or address")
    bridge = FoxgloveBridge(
        ctx.runtime,
        params,
        dialect=ctx.spec.dialect,
        package_index=ctx.shared.package_index,
        name=name,
        namespace=ctx.namespace,
        address=address or "127.0.0.1",
        port=_number(settings.get("port", 8765), "port", fqn, low=0, high=65535),
        topic_whitelist=_strings(settings.get("topic_whitelist", [".*"]), "topic_whitelist", fqn),
        param_whitelist=_strings(settings.get("param_whitelist", [".*"]), "param_whitelist", fqn),
        service_whitelist=_strings(settings.get("service_whitelist", [".*"]),
                                   "service_whitelist", fqn),
        client_topic_whitelist=_strings(settings.get("client_topic_whitelist", [".*"]),
                                        "client_topic_whitelist", fqn),
        asset_uri_allowlist=_strings(settings.get("asset_uri_allowlist",
                                                  list(DEFAULT_ASSET_ALLOWLIST)),
                                     "asset_uri_allowlist", fqn),
        use_sim_time=_flag(settings.get("use_sim_time", False), "use_sim_time", fqn),
        send_buffer_limit=_number(settings.get("send_buffer_limit", 10_000_000),
                                  "send_buffer_limit", fqn, low=1024, high=2**31),
        max_qos_depth=_number(settings.get("max_qos_depth", 25), "max_qos_depth", fqn,
                              low=1, high=10_000),
        capabilities=_strings(settings.get("capabilities", list(CAPABILITIES)), "capabilities", fqn),
        log=ctx.log,
    )  # fmt: skip
    return _BridgeNode(bridge)


@register("ros1", "foxglove_bridge", "foxglove_bridge",
          purpose="the Foxglove WebSocket protocol (port 8765) for Foxglove and Lichtblick")  # fmt: skip
def foxglove_bridge_ros1(ctx: NodeContext) -> RunningNode:
    from robomodel.bridges.rosapi import Ros1Params

    settings = {k: ctx.param(f"~{k}") for k in _FOXGLOVE if ctx.param(f"~{k}") is not None}
    settings["use_sim_time"] = ctx.use_sim_time  # ROS 1's is the global /use_sim_time
    return _start_foxglove(
        ctx, settings, Ros1Params(ctx.params), ctx.spec.name or "foxglove_bridge"
    )


@register("ros2", "foxglove_bridge", "foxglove_bridge",
          purpose="the Foxglove WebSocket protocol (port 8765) for Foxglove and Lichtblick")  # fmt: skip
def foxglove_bridge_ros2(ctx: NodeContext) -> RunningNode:
    from robomodel.bridges.rosapi import Ros2Params

    name = ctx.spec.name or "foxglove_bridge"
    settings = {k: v for k, v in ctx.ros2_parameters(name).items() if k in _FOXGLOVE}
    runtime = ctx.runtime
    params = Ros2Params(runtime, lambda: sorted(runtime.graph(timeout_s=0.3).nodes), 1.0)
    return _start_foxglove(ctx, settings, params, name)
