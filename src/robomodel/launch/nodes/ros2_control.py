"""ros2_control nodes of a ROS 2 launch file: ``ros2_control_node`` (the controller manager on
the robot's ``<ros2_control>`` hardware), ``spawner`` and ``unspawner``.

``ros2_control_node`` takes ``robot_description`` from its parameter (Humble) or, without one,
from the launch's robot_state_publisher (Jazzy's ``robot_description`` topic), its
``update_rate`` and controller types from its parameters (YAML files with node-name keys), and
each controller's parameters from the same files under the controller's name, as controller
nodes get them. A hardware plugin robomodel does not have (a demo's own C++ system) runs as
``mock_components/GenericSystem`` over the interfaces its tag declares, with one warning. The
manager is named as the launch file names the node (``name="my_ctrl_mgr"``), so spawners'
``-c my_ctrl_mgr`` find it.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

from robomodel.launch.model import NodeSpec
from robomodel.launch.nodes.base import NodeContext, RunningNode, ThreadNode, register
from robomodel.launch.nodes.controllers import wait_for_manager
from robomodel.launch.nodes.ros2_spawner_args import Ros2SpawnerArgs, parse_ros2_spawner_args

if TYPE_CHECKING:
    from robomodel.control.client import ManagerClient

__all__ = ["Ros2SpawnerArgs", "parse_ros2_spawner_args"]


def _nest(flat: dict[str, Any]) -> dict[str, Any]:
    out: dict[str, Any] = {}
    for key, value in flat.items():
        parts = key.split(".")
        here = out
        for part in parts[:-1]:
            here = here.setdefault(part, {})
        here[parts[-1]] = value
    return out


def unknown_types(spec: NodeSpec, manager_name: str) -> dict[str, str]:
    """Controllers the manager's parameters give a type robomodel does not have: name -> type.
    ros2_control reports those when a spawner loads them, not when the manager starts."""
    from robomodel.control.config import ROS1_TYPES
    from robomodel.control.controllers.registry import CONTROLLER_TYPES
    from robomodel.launch.nodes.ros2_params import node_parameters

    params = node_parameters(spec, name=manager_name)
    return {
        key.rsplit(".", 1)[0]: str(value)
        for key, value in params.items()
        if key.endswith(".type") and value not in CONTROLLER_TYPES and value not in ROS1_TYPES
    }


def controller_config_text(spec: NodeSpec, manager_name: str) -> str:
    """The manager's and its controllers' parameters as one ros2_control YAML document
    (controllers of types robomodel does not have left out: see :func:`unknown_types`)."""
    import dataclasses

    import yaml

    from robomodel.launch.nodes.ros2_params import node_parameters

    unknown = unknown_types(spec, manager_name)
    params = node_parameters(spec, name=manager_name)
    params.pop("robot_description", None)
    for name in unknown:
        params = {k: v for k, v in params.items() if not k.startswith(name + ".")}
    doc: dict[str, Any] = {"controller_manager": {"ros__parameters": _nest(params)}}
    names = sorted({k.rsplit(".", 1)[0] for k in params if k.endswith(".type")})
    for name in names:
        pseudo = dataclasses.replace(spec, name=name)
        own = node_parameters(pseudo, name=name)
        own.pop("robot_description", None)
        if own:
            doc[name] = {"ros__parameters": _nest(own)}
    return yaml.safe_dump(doc, sort_keys=False)


class ManagerNode:
    """A running ros2_control_node (its node's warnings reach the launch's output through
    :mod:`robomodel.launch.node_log`)."""

    def __init__(self, system: Any) -> None:
        self.system = system
        self._code: int | None = None

    def stop(self) -> None:
        if self._code is None:
            self._code = 0
            self.system.manager.close()

    def exit_code(self) -> int | None:
        return self._code


@register(
    "ros2",
    "controller_manager",
    "ros2_control_node",
    purpose="robomodel's controller manager on the description's <ros2_control> hardware",
)
def ros2_control_node(ctx: NodeContext) -> RunningNode:
    from robomodel.control import ControlSystem
    from robomodel.control.config import load_controller_config
    from robomodel.description import read_urdf
    from robomodel.launch.nodes.ros2_nodes import robot_description_of

    name = ctx.spec.name or "controller_manager"
    params = ctx.ros2_parameters(name)
    robot = read_urdf(robot_description_of(ctx, params)).robot
    source = next((str(p.file) for p in ctx.spec.parameters if p.file is not None), ctx.spec.fqn)
    config = load_controller_config(source, text=controller_config_text(ctx.spec, name))
    import dataclasses

    config = dataclasses.replace(config, namespace=ctx.namespace)
    unknown = unknown_types(ctx.spec, name)

    def prepare(manager: Any) -> None:
        if unknown:
            manager.spec_source = _not_found(unknown)

    system = ControlSystem.build(
        robot,
        config,
        context=ctx.runtime,
        spawn=[],
        name=name,
        unknown_hardware_as_mock=True,
        prepare=prepare,
    )
    system.manager.start()
    ctx.log(
        f"controller manager {system.manager.service_prefix} at {system.manager.update_rate_hz} "
        f"Hz on {', '.join(c.name for c in system.resources.components)}"
    )
    return ManagerNode(system)


def _not_found(unknown: dict[str, str]) -> Any:
    from robomodel.control.controllers.registry import CONTROLLER_TYPES
    from robomodel.control.exceptions import ControlError

    def source(name: str) -> None:
        if name in unknown:
            raise ControlError(
                f"Loader for controller '{name}' (type '{unknown[name]}') not found. Available "
                f"classes: {', '.join(sorted(CONTROLLER_TYPES))}"
            )

    return source


def spawner_param_files(spec: NodeSpec, options: Ros2SpawnerArgs) -> tuple[str, ...]:
    """``--param-file`` files, then the spawner node's own parameter files (what launch_ros
    passes it as ``--ros-args --params-file``), each once: Jazzy's spawner (ros2_control 4.x,
    controller_manager/spawner.py) gives them all to every controller it loads. A node's
    parameters given as a dict (a temporary file in launch_ros) are not passed on."""
    files = [*options.param_files, *(str(p.file) for p in spec.parameters if p.file is not None)]
    return tuple(dict.fromkeys(files))


def _files_for(files: tuple[str, ...], fqn: str) -> tuple[str, ...]:
    """The files with parameters for controller ``fqn`` (its name, ``/ns/name``, a ``/**``
    wildcard), as Jazzy's ``get_params_files_with_controller_parameters`` picks them."""
    from robomodel.runtime.param_files import parameters_from_file

    return tuple(f for f in files if parameters_from_file(Path(f), fqn))


def _in_namespace(options: Ros2SpawnerArgs) -> str:
    """``-c`` under the deprecated ``-n/--namespace`` (Jazzy's spawner puts a relative
    manager name there instead of in the node's namespace)."""
    name = options.controller_manager
    if options.namespace and not name.startswith("/"):
        return "/" + options.namespace.strip("/") + "/" + name
    return name


def _manager_path(ctx: NodeContext, name: str) -> str:
    """``-c NAME`` as the spawner's node resolves it (relative: in its namespace; remaps)."""
    return ctx.resolve_name(name.rstrip("/") or "/")


def _client(ctx: NodeContext, path: str, options: Ros2SpawnerArgs) -> ManagerClient:
    from robomodel.control.client import AttemptsClient

    return AttemptsClient(
        ctx.runtime, path, call_timeout_s=options.service_call_timeout_s, warn=ctx.log
    )


def _wait(ctx: NodeContext, node: ThreadNode, path: str, options: Ros2SpawnerArgs) -> bool:
    """Wait for the manager's services (``--controller-manager-timeout``; 0: for ever)."""
    timeout_s = options.timeout_s
    ready = wait_for_manager(
        ctx,
        node,
        path,
        timeout_s,
        call_timeout_s=options.service_call_timeout_s,
        zero_waits_forever=True,
    )
    if ready is False:
        ctx.log(f"Controller manager not available: {path} (after {timeout_s:g} s)")
    return bool(ready)


@register(
    "ros2",
    "controller_manager",
    "spawner",
    "spawner.py",  # Foxy's name
    purpose="loads, configures and activates controllers (-c, -p, --inactive, --load-only, "
    "--activate-as-group, -u)",
)
def spawner(ctx: NodeContext) -> RunningNode:
    options = parse_ros2_spawner_args(ctx.spec.args)
    path = _manager_path(ctx, _in_namespace(options))
    files = spawner_param_files(ctx.spec, options)

    def work(node: ThreadNode) -> int:
        missing = [f for f in files if not Path(f).is_file()]
        if missing:
            ctx.log(f"[Errno 2] No such file or directory: '{missing[0]}'")
            return 1
        if not _wait(ctx, node, path, options):
            return 1
        client = _client(ctx, path, options)
        listed = {c.name for c in client.list_controllers()}
        loaded: list[str] = []
        code = 0
        for name in options.controllers:
            if name in listed:
                ctx.log(f"Controller already loaded, skipping load_controller: {name}")
                loaded.append(name)
                continue
            client.set_controller_parameters(
                name,
                type_name=options.controller_type,
                params_files=_files_for(files, f"{ctx.namespace.rstrip('/')}/{name}"),
            )
            if not client.load(name):
                ctx.log(f"Failed loading controller {name}")
                code = 1
                continue
            ctx.log(f"Loaded {name}")
            loaded.append(name)
        if options.load_only:
            return code
        for name in loaded:
            if not client.configure(name):
                ctx.log(f"Failed to configure controller {name}")
                code = 1
        if not options.inactive:
            groups = [loaded] if options.activate_as_group else [[n] for n in loaded]
            for group in groups:
                ok, message = client.switch(group, [], 2, timeout_s=options.switch_timeout_s)
                if ok:
                    ctx.log(f"Configured and activated {', '.join(group)}")
                else:
                    ctx.log(f"Failed to activate controller {', '.join(group)}: {message}")
                    code = 1
        if options.unload_on_kill:
            node.stopping.wait()
            client.switch([], loaded, 1)
            for name in reversed(loaded):
                client.unload(name)
        return code

    return ThreadNode(f"spawner {ctx.spec.fqn}", work, ctx.log)


@register(
    "ros2",
    "controller_manager",
    "unspawner",
    "unspawner.py",  # Foxy's name
    purpose="deactivates and unloads controllers",
)
def unspawner(ctx: NodeContext) -> RunningNode:
    options = parse_ros2_spawner_args(ctx.spec.args)
    path = _manager_path(ctx, _in_namespace(options))

    def work(node: ThreadNode) -> int:
        if not _wait(ctx, node, path, options):
            return 1
        client = _client(ctx, path, options)
        names = list(options.controllers)
        client.switch([], names, 1)
        code = 0
        for name in names:
            if client.unload(name):
                ctx.log(f"Unloaded {name}")
            else:
                code = 1
        return code

    return ThreadNode(f"unspawner {ctx.spec.fqn}", work, ctx.log)
