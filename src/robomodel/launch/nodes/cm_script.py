"""ROS 1's ``controller_manager`` script (``rosrun controller_manager controller_manager
<command> <controller>...``), with its commands, aliases and printed words.

Transcribed from ros_control noetic-devel 0.20.0 (ros-controls/ros_control,
controller_manager/scripts/controller_manager and src/controller_manager/
controller_manager_interface.py): ``list`` prints ``'<name>' - '<interfaces>' ( <state> )``
with ROS 1's states (running, stopped, initialized), or ``No controllers are loaded in
mechanism control``; ``load`` prints ``Loaded '<name>'``; ``unload`` ``Unloaded '<name>'
successfully``; ``start``/``stop`` ``Started ['<name>'] successfully``; ``spawn`` loads then
starts each, ``kill`` stops then unloads each; ``reload-libraries [--restore]``.

The services are those of ``<namespace>/controller_manager`` (the script's relative
``controller_manager/...`` names, resolved in the node's namespace: ``__ns:=/rrbot``).
"""

from __future__ import annotations

from typing import Any

from robomodel.errors import RobomodelError, describe_unknown
from robomodel.launch.nodes.base import NodeContext, RunningNode, ThreadNode, register

__all__ = ["format_controller_line"]

_ALIASES = {"lt": "list-types", "lc": "list", "sp": "spawn", "kl": "kill"}
_COMMANDS = (
    "load", "unload", "start", "stop", "spawn", "kill", "list", "list-types", "reload-libraries",
)  # fmt: skip
_STATES = {"active": "running", "inactive": "stopped", "unconfigured": "initialized"}


def format_controller_line(entry: Any) -> str:
    """One line of ``controller_manager list`` for a ControllerState (ROS 2 fields)."""
    from robomodel.runtime.transport.ros1.ros1_fields import ros1_hardware_interface

    # ROS 1 reports a controller's claims whatever its state; ROS 2 claims only while active
    claimed = entry.claimed_interfaces or entry.required_command_interfaces
    kinds = {str(i).rpartition("/")[2] for i in claimed}
    interfaces = sorted(ros1_hardware_interface(kind) for kind in kinds)
    if not interfaces and "JointState" in entry.type:
        # ROS 1's JointStateController claims the JointStateInterface, without resources
        interfaces = ["hardware_interface::JointStateInterface"]
    state = _STATES.get(entry.state, entry.state)
    return f"'{entry.name}' - '{'+'.join(interfaces)}' ( {state} )"


class _Script:
    """The script's commands on one controller manager; each returns whether it succeeded."""

    def __init__(self, ctx: NodeContext) -> None:
        from robomodel.control.client import ManagerClient

        self.prefix = ctx.spec.namespace.rstrip("/") + "/controller_manager"
        # ROS 1's script calls each service with no deadline, once it is there
        self.client = ManagerClient(ctx.runtime, self.prefix, timeout_s=300.0)

    def list_controllers(self) -> bool:
        controllers = self.client.list_controllers()
        if not controllers:
            print("No controllers are loaded in mechanism control", flush=True)
        for entry in controllers:
            print(format_controller_line(entry), flush=True)
        return True

    def list_types(self) -> bool:
        for name in self.client.list_types():
            print(name, flush=True)
        return True

    def load(self, name: str) -> bool:
        ok = self.client.load(name) and self.client.configure(name)
        print(f"Loaded '{name}'" if ok else f"Error when loading '{name}'", flush=True)
        return ok

    def unload(self, name: str) -> bool:
        ok = self.client.unload(name)
        print(
            f"Unloaded '{name}' successfully" if ok else f"Error when unloading '{name}'",
            flush=True,
        )
        return ok

    def switch(self, start: list[str], stop: list[str]) -> bool:
        ok, _ = self.client.switch(start, stop)  # STRICT, as the script asks
        if not ok:
            print(f"Error when starting {start} and stopping {stop}", flush=True)
            return False
        if start:
            print(f"Started {start} successfully", flush=True)
        if stop:
            print(f"Stopped {stop} successfully", flush=True)
        return True

    def reload_libraries(self, restore: bool) -> bool:
        from robomodel.runtime.msg.types import controller_manager_msgs as cm_msgs

        print(f"Restore: {restore}", flush=True)
        before = self.client.list_controllers() if restore else []
        reply = self.client.call(
            "reload_controller_libraries",
            cm_msgs.ReloadControllerLibraries,
            cm_msgs.ReloadControllerLibraries_Request(force_kill=True),
        )
        if reply.ok:
            print("Successfully reloaded libraries", flush=True)
        else:
            print("Failed to reload libraries. Do you still have controllers loaded?", flush=True)
        if restore:
            for entry in before:
                if self.client.load(entry.name):
                    self.client.configure(entry.name)
            running = [e.name for e in before if e.state == "active"]
            self.client.switch(running, [], 1)  # BEST_EFFORT
            print("Controllers restored to original state", flush=True)
        return bool(reply.ok)


def _run(script: _Script, command: str, names: list[str]) -> bool:
    if command == "list":
        return script.list_controllers()
    if command == "list-types":
        return script.list_types()
    if command == "reload-libraries":
        return script.reload_libraries("--restore" in names)
    ok = True
    if command in ("load", "spawn"):
        ok = all([script.load(n) for n in names])
    if command in ("stop", "kill"):
        ok = all([script.switch([], [n]) for n in names]) and ok
    if command in ("start", "spawn"):
        ok = all([script.switch([n], []) for n in names]) and ok
    if command in ("unload", "kill"):
        ok = all([script.unload(n) for n in names]) and ok
    return ok


def _waiting_hint(ctx: NodeContext, prefix: str) -> str:
    """Where the script waits, and the controller managers the graph has instead."""
    suffix = "/controller_manager/list_controllers"
    try:
        services = ctx.runtime.graph(timeout_s=1.0).services
    except Exception:  # the hint is a courtesy: no graph, no list
        services = {}
    others = sorted(name[: -len(suffix)] or "/" for name in services if name.endswith(suffix))
    where = (
        f"; controller managers on the graph are in: {', '.join(others)} (give __ns:=NS)"
        if others
        else "; no controller manager is on the graph yet"
    )
    return f"waiting for service {prefix}/list_controllers{where}"


@register(
    "ros1",
    "controller_manager",
    "controller_manager",
    purpose="controller_manager load|unload|start|stop|spawn|kill|list|list-types|"
    "reload-libraries NAME... on robomodel's controller manager (ROS 1's words)",
)
def controller_manager(ctx: NodeContext) -> RunningNode:
    args = [a for a in ctx.spec.args if ":=" not in a]
    if not args:
        raise RobomodelError(
            f"controller_manager: give a command; commands are {', '.join(_COMMANDS)}"
        )
    command = _ALIASES.get(args[0], args[0])
    if command not in _COMMANDS:
        raise RobomodelError(
            describe_unknown("controller_manager: unknown command", args[0], _COMMANDS,
                             "commands are")
        )  # fmt: skip
    script = _Script(ctx)

    def work(node: ThreadNode) -> int:
        from robomodel.launch.nodes.controllers import wait_for_manager

        # ROS 1's script waits for the service without a word; robomodel says where it waits
        ready = wait_for_manager(ctx, node, script.prefix, 2.0, call_timeout_s=2.0)
        if ready is False:
            ctx.log(_waiting_hint(ctx, script.prefix))
            ready = wait_for_manager(ctx, node, script.prefix, 0.0, zero_waits_forever=True)
        if not ready:
            return 0 if node.stopping.is_set() else 1
        return 0 if _run(script, command, args[1:]) else 1

    return ThreadNode(f"controller_manager {ctx.spec.fqn}", work, ctx.log)
