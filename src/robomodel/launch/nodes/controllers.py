"""controller_manager nodes of a ROS 1 launch file: ``spawner``, ``controller_manager`` and
``unspawner`` (controller_manager 0.19's scripts), talking to a controller manager over the
bus as the scripts do over ROS services, each from its own thread as from its own process.

The controller manager is the one robomodel's simulator runs for a robot (``gazebo_ros_control``,
``<namespace>/controller_manager``), in this launch or in another robomodel process of the
domain. It takes a controller's type and parameters from the parameter server at
``<namespace>/<controller>`` (what ``<rosparam file=... command="load"/>`` put there), as
ROS 1's controller_manager does.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from robomodel.errors import RobomodelError
from robomodel.launch.nodes.base import NodeContext, RunningNode, ThreadNode, register

if TYPE_CHECKING:
    from robomodel.control.config import ControllerSpec

__all__ = ["SpawnerArgs", "parse_spawner_args", "ros1_spec_source", "wait_for_manager"]


def ros1_spec_source(params: Any) -> Callable[[str, str], ControllerSpec | None]:
    """Controller specs read from the ROS 1 parameter server, as controller_manager's
    ``loadController`` reads ``<namespace>/<name>/type`` and the controller its parameters."""

    def source(namespace: str, name: str) -> ControllerSpec | None:
        import yaml

        from robomodel.control.config import load_controller_config
        from robomodel.control.exceptions import ConfigError

        key = f"{namespace.rstrip('/')}/{name}"
        value = params.get(key) if params.has(key) else None
        if not isinstance(value, dict) or "type" not in value:
            raise ConfigError(
                f"Could not load controller '{name}' because controller type is not specified. "
                "Did you load the controller configuration on the parameter server (namespace: "
                f"'{key}')?"
            )
        text = yaml.safe_dump({name: value})
        return load_controller_config(f"<parameter server {key}>", text=text).controllers[0]

    return source


@dataclass(frozen=True, slots=True)
class SpawnerArgs:
    """The ROS 1 spawner's command line."""

    controllers: tuple[str, ...]
    stopped: bool = False
    namespace: str | None = None
    timeout_s: float = 30.0
    shutdown_timeout_s: float = 30.0
    wait_for: str | None = None


def parse_spawner_args(args: tuple[str, ...]) -> SpawnerArgs:
    """controller_manager/spawner's options (argparse, ``--opt=value`` or ``--opt value``)."""
    names: list[str] = []
    values: dict[str, str] = {}
    stopped = False
    i = 0
    while i < len(args):
        token = args[i]
        option, eq, inline = token.partition("=")
        if option == "--stopped":
            stopped = True
        elif option in ("--namespace", "--timeout", "--shutdown-timeout", "--wait-for"):
            if eq:
                values[option] = inline
            elif i + 1 < len(args):
                values[option] = args[i + 1]
                i += 1
            else:
                raise RobomodelError(f"spawner: {option} needs a value")
        elif token.startswith("__"):  # __name:=, __log:= added by roslaunch
            pass
        elif token.startswith("-"):
            raise RobomodelError(
                f"spawner: unrecognized argument '{token}'; options are --stopped, --namespace, "
                "--timeout, --shutdown-timeout, --wait-for"
            )
        else:
            names.append(token)
        i += 1
    if not names:
        raise RobomodelError("spawner: give at least one controller name")
    return SpawnerArgs(
        tuple(names),
        stopped,
        values.get("--namespace"),
        _seconds(values, "--timeout", 30.0),
        _seconds(values, "--shutdown-timeout", 30.0),
        values.get("--wait-for"),
    )


def _seconds(values: dict[str, str], option: str, default: float) -> float:
    if option not in values:
        return default
    try:
        return float(values[option])
    except ValueError:
        raise RobomodelError(f"spawner: {option} needs a number of seconds") from None


def wait_for_manager(
    ctx: NodeContext,
    node: ThreadNode,
    manager: str,
    timeout_s: float,
    *,
    call_timeout_s: float | None = None,
    zero_waits_forever: bool = False,
) -> bool | None:
    """Poll ``manager``'s ``list_controllers`` until it answers (True), ``timeout_s`` passes
    (False; with ``zero_waits_forever``, a timeout of 0 never passes) or the node is stopped
    (None), as the spawners wait for their controller manager's services.

    A service that is not offered fails at once; one that is offered but slow to answer (a
    loaded machine) is waited for until the spawner's own deadline: each poll may take
    ``call_timeout_s``, by default the time left (10 s a poll when waiting forever).
    """
    from robomodel.control.client import ManagerClient

    client = ManagerClient(ctx.runtime, manager)
    forever = zero_waits_forever and timeout_s <= 0
    deadline = time.monotonic() + timeout_s
    while not node.stopping.is_set():
        left_s = deadline - time.monotonic()
        poll_s = call_timeout_s if call_timeout_s is not None else 10.0 if forever else left_s
        try:
            client.list_controllers(timeout_s=max(0.2, poll_s))
            if _offers(ctx, manager, _SPAWNER_SERVICES):
                return True
        except RobomodelError:
            if not forever and time.monotonic() > deadline:
                return False
            node.stopping.wait(0.2)
    return None


_SPAWNER_SERVICES = ("load_controller", "switch_controller")
"""What a spawner calls after list_controllers: a manager registers its services one by one, and
on a ROS 1 master a spawner that called load_controller as soon as list_controllers answered
found no provider yet (rospy's spawner waits for load_controller itself)."""


def _offers(ctx: NodeContext, manager: str, services: tuple[str, ...]) -> bool:
    offered = ctx.runtime.graph(timeout_s=1.0).services
    return all(f"{manager}/{name}" in offered for name in services)


class _Manager:
    """Calls to one controller manager's services, with the spawner scripts' messages."""

    def __init__(self, ctx: NodeContext, namespace: str | None) -> None:
        from robomodel.control.client import NO_DEADLINE_S, ManagerClient

        # the script's relative ``<namespace/>controller_manager/...``, resolved by rospy in
        # the spawner's namespace and remaps
        base = namespace.rstrip("/") + "/" if namespace else ""
        self.prefix = ctx.resolve_name(base + "controller_manager")
        self.ctx = ctx
        # the scripts wait for the services up to --timeout, then call them without a deadline
        self.client = ManagerClient(ctx.runtime, self.prefix, timeout_s=NO_DEADLINE_S)

    def wait(self, node: ThreadNode, timeout_s: float) -> bool:
        self.ctx.log(f"Controller Spawner: Waiting for service {self.prefix}/load_controller")
        ready = wait_for_manager(self.ctx, node, self.prefix, timeout_s)
        if ready is False:
            self.ctx.log(
                f"Controller Spawner couldn't find the expected controller_manager ROS "
                f"interface ({self.prefix}: no robomodel process runs it; start the "
                "simulation first, e.g. the launch file with gazebo_ros)"
            )
        return bool(ready)

    def load(self, name: str) -> bool:
        """ROS 1's ``load_controller``: loaded and initialized, i.e. ROS 2's inactive."""
        ok = self.client.load(name) and self.client.configure(name)
        if not ok:
            self.ctx.log(f"Failed to load {name} (the controller manager logs why)")
        return ok

    def switch(self, start: list[str], stop: list[str], strictness: int = 2) -> bool:
        ok, message = self.client.switch(start, stop, strictness)
        if not ok:
            self.ctx.log(f"switch_controller failed: {message or 'unknown error'}")
        return ok

    def unload(self, name: str) -> bool:
        return self.client.unload(name)


@register(
    "ros1",
    "controller_manager",
    "spawner",
    purpose="loads and starts controllers in robomodel's controller manager; stops and unloads "
    "them when the launch ends",
)
def spawner(ctx: NodeContext) -> RunningNode:
    options = parse_spawner_args(ctx.spec.args)
    manager = _Manager(ctx, options.namespace)

    def work(node: ThreadNode) -> int:
        if not manager.wait(node, options.timeout_s):
            return 1 if not node.stopping.is_set() else 0
        loaded = []
        for name in options.controllers:
            ctx.log(f"Loading controller: {name}")
            if manager.load(name):
                loaded.append(name)
        ctx.log(f"Controller Spawner: Loaded controllers: {', '.join(loaded)}")
        if loaded and not options.stopped:
            if manager.switch(loaded, []):
                ctx.log(f"Started controllers: {', '.join(loaded)}")
            else:
                ctx.log(f"Failed to start controllers: {', '.join(loaded)}")
        node.stopping.wait()
        _shutdown(manager, loaded)  # the spawner's shutdown hook
        return 0

    return ThreadNode(f"spawner {ctx.spec.fqn}", work, ctx.log)


def _shutdown(manager: _Manager, loaded: list[str]) -> None:
    try:
        manager.switch([], loaded, strictness=1)
        for name in reversed(loaded):
            manager.unload(name)
    except RobomodelError:
        pass  # the manager's process has ended already


@register(
    "ros1",
    "controller_manager",
    "unspawner",
    purpose="stops and unloads controllers while it runs; loads and starts them again at the end",
)
def unspawner(ctx: NodeContext) -> RunningNode:
    names = [a for a in ctx.spec.args if not a.startswith("-") and not a.startswith("__")]
    if not names:
        raise RobomodelError("unspawner: give at least one controller name")
    manager = _Manager(ctx, None)

    def work(node: ThreadNode) -> int:
        if not manager.wait(node, 30.0):
            return 1
        manager.switch([], names, strictness=1)
        for name in names:
            manager.unload(name)
        node.stopping.wait()
        for name in names:
            manager.load(name)
        manager.switch(names, [])
        return 0

    return ThreadNode(f"unspawner {ctx.spec.fqn}", work, ctx.log)
