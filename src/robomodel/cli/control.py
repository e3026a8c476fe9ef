"""``robomodel control``: the controller manager over the bus, like ``ros2 control``.

``run FILE --controllers CONFIG.yaml`` is the seeds' ``ros2_control_node`` + spawner +
robot_state_publisher (+ RViz) launch: mock hardware from the description, the controller
manager at ``update_rate`` on the wall clock, every controller of the file loaded, configured
and activated, and robot_state_publisher fed by the joint_state_broadcaster. The other verbs
call the manager's services from another process.
"""

from __future__ import annotations

import argparse
import contextlib
import importlib
import sys
import webbrowser
from typing import Any

from robomodel.cli._bus import (
    add_bus_arguments,
    bus_from_args,
    context_from_args,
    settled_graph,
    wait_for_peers,
)
from robomodel.cli._common import (
    add_description_arguments,
    add_frame_rate_argument,
    load_from_args,
)
from robomodel.cli._ports import add_port_argument
from robomodel.cli._verbs import verb_help
from robomodel.errors import RobomodelError

__all__ = ["register"]


def _cm_argument(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "-c",
        "--controller-manager",
        default="/controller_manager",
        help="the controller manager's node name (default: /controller_manager)",
    )
    add_bus_arguments(parser)


def register(subparsers: Any) -> None:
    parser = subparsers.add_parser("control", help=verb_help("control"))
    verbs = parser.add_subparsers(dest="control_verb", metavar="VERB")
    verbs.required = True
    _register_run(verbs)
    _register_manager_verbs(verbs)


def _register_run(verbs: Any) -> None:
    """``control run``: ros2_control_node with mock hardware, the spawner and a viewer."""
    run_p = verbs.add_parser("run", help="mock hardware + controller manager + controllers")
    add_description_arguments(run_p)
    run_p.add_argument(
        "--controllers",
        required=True,
        metavar="CONFIG.yaml",
        help="controller YAML (ROS 2 or ROS 1)",
    )
    run_p.add_argument("--no-view", action="store_true", help="do not start the viewer")
    run_p.add_argument(
        "--no-browser", action="store_true", help="start the viewer but do not open a browser"
    )
    add_port_argument(run_p, "the viewer's HTTP port")
    add_frame_rate_argument(run_p)
    run_p.add_argument(
        "--inactive", action="store_true", help="load and configure only (spawner --inactive)"
    )
    run_p.add_argument(
        "--no-spawn",
        action="store_true",
        help="load nothing (ros2_control_node alone); then `robomodel control load NAME`",
    )
    run_p.add_argument("--duration", type=float, default=None, help="stop after S seconds")
    run_p.add_argument("--update-rate", type=int, default=None, help="override update_rate [Hz]")
    add_bus_arguments(run_p)
    run_p.set_defaults(func=_run)


def _register_manager_verbs(verbs: Any) -> None:
    """The verbs that call a running controller manager (``ros2 control ...``)."""
    lc = verbs.add_parser("list-controllers", help="controllers, types and states")
    lc.add_argument("-v", "--verbose", action="store_true", help="also rates and interfaces")
    _cm_argument(lc)
    lc.set_defaults(func=_list_controllers)

    lt = verbs.add_parser("list-controller-types", help="the controller types available")
    _cm_argument(lt)
    lt.set_defaults(func=_list_types)

    lcomp = verbs.add_parser("list-hardware-components", help="hardware components and states")
    _cm_argument(lcomp)
    lcomp.set_defaults(func=_list_components)

    lh = verbs.add_parser("list-hardware-interfaces", help="command and state interfaces")
    _cm_argument(lh)
    lh.set_defaults(func=_list_interfaces)

    load = verbs.add_parser("load", help="load a controller of the manager's configuration")
    load.add_argument("name")
    load.add_argument(
        "--set-state",
        choices=("inactive", "active", "configure", "start"),
        default=None,
        help="also configure (inactive) or activate it; 'configure'/'start' are the old names",
    )
    _cm_argument(load)
    load.set_defaults(func=_load)

    sw = verbs.add_parser("switch", help="activate and deactivate controllers")
    sw.add_argument("--activate", nargs="*", default=[], metavar="NAME")
    sw.add_argument("--deactivate", nargs="*", default=[], metavar="NAME")
    sw.add_argument("--strict", action="store_true", help="fail the whole request on any error")
    _cm_argument(sw)
    sw.set_defaults(func=_switch)

    for verb, helptext in (
        ("unload", "unload an inactive controller"),
        ("configure", "configure a loaded controller"),
        ("cleanup", "clean up an inactive controller"),
    ):
        p = verbs.add_parser(verb, help=helptext)
        p.add_argument("name")
        _cm_argument(p)
        p.set_defaults(func=_simple, service=f"{verb}_controller")


def _with_manager(args: argparse.Namespace, action: Any) -> Any:
    """``action(client)`` against the controller manager the arguments name."""
    from robomodel.control.client import AttemptsClient

    cm = "/" + args.controller_manager.strip("/")
    with context_from_args(args) as context:
        wait_for_peers(context)
        _refuse_if_elsewhere(context, cm)
        # ros2controlcli's service_caller: 10 s per attempt, 3 attempts, a warning after each
        # (a busy manager answers late; with none on the bus the call waits for one to start)
        client = AttemptsClient(
            context,
            cm,
            call_timeout_s=10.0,
            attempts=3,
            warn=lambda line: print(line, file=sys.stderr),
        )
        try:
            return action(client)
        except RobomodelError as exc:
            managers = _managers_on_the_bus(context)
            if cm in managers:  # it answered, refusing: asking whether it runs would mislead
                raise
            if managers:  # all of them others: cm is not among them
                hint = _elsewhere(cm, managers)
            else:
                hint = f"is `robomodel control run` running (controller manager {cm})?"
            raise RobomodelError(f"{exc}; {hint}") from None


def _elsewhere(cm: str, others: list[str]) -> str:
    return (
        f"controller manager {cm} is not on the bus; controller managers that are: "
        f"{', '.join(others)} (pass -c {others[0]})"
    )


def _refuse_if_elsewhere(context: Any, cm: str) -> None:
    """Say at once that ``cm`` is not on the bus when other managers are, rather than wait
    for it. One look at the graph finds a manager that is there; only when it does not is the
    graph let settle (~0.5 s), so the usual call pays nothing for the check."""
    if cm in _managers(context.graph(timeout_s=0.5)):
        return
    managers = _managers_on_the_bus(context)
    if managers and cm not in managers:  # others are there: do not wait for this one
        raise RobomodelError(_elsewhere(cm, managers))


def _managers_on_the_bus(context: Any) -> list[str]:
    """The controller managers the settled graph shows."""
    return _managers(settled_graph(context, 1.0))


def _managers(graph: Any) -> list[str]:
    """Whatever offers ``<manager>/list_controllers`` (ros2_control's and ROS 1
    controller_manager's service name)."""
    suffix = "/list_controllers"
    services = graph.services
    return sorted(
        name[: -len(suffix)]
        for name, info in services.items()
        if name.endswith(suffix) and info.servers  # not another caller's client
    )


def _check(ok: bool, what: str) -> None:
    if not ok:
        raise RobomodelError(f"{what} failed; the controller manager's log says why")


def _list_controllers(args: argparse.Namespace) -> int:
    controllers = _with_manager(args, lambda c: c.list_controllers())
    wn = max((len(c.name) for c in controllers), default=0)
    wt = max((len(c.type) for c in controllers), default=0)
    for c in controllers:  # ros2controlcli list_controllers format
        print(f"{c.name:<{wn}} {c.type:<{wt}}  {c.state}")
        if args.verbose:
            print(f"\tupdate_rate: {c.update_rate} Hz")
            print("\tclaimed interfaces:")
            for i in c.claimed_interfaces:
                print(f"\t\t{i}")
            print("\trequired state interfaces:")
            for i in c.required_state_interfaces:
                print(f"\t\t{i}")
    return 0


def _list_types(args: argparse.Namespace) -> int:
    for name in _with_manager(args, lambda c: c.list_types()):
        print(name)
    return 0


def _list_components(args: argparse.Namespace) -> int:
    for k, c in enumerate(_with_manager(args, lambda c: c.list_components())):
        print(f"Hardware Component {k + 1}\n\tname: {c.name}\n\ttype: {c.type}")
        print(f"\tplugin name: {c.plugin_name}\n\tstate: id={c.state.id} label={c.state.label}")
    return 0


def _list_interfaces(args: argparse.Namespace) -> int:
    answer = _with_manager(args, lambda c: c.list_interfaces())
    print("command interfaces")
    for i in answer.command_interfaces:
        available = "available" if i.is_available else "unavailable"
        claimed = "claimed" if i.is_claimed else "unclaimed"
        print(f"\t{i.name} [{available}] [{claimed}]")
    print("state interfaces")
    for i in answer.state_interfaces:
        print(f"\t{i.name}")
    return 0


def _load(args: argparse.Namespace) -> int:
    state = {"configure": "inactive", "start": "active"}.get(args.set_state, args.set_state)

    def load(client: Any) -> None:
        _check(client.load(args.name), f"loading controller {args.name}")
        if state in ("inactive", "active"):
            _check(client.configure(args.name), f"configuring controller {args.name}")
        if state == "active":
            ok, message = client.switch([args.name], [], 2)
            if not ok:
                raise RobomodelError(f"activating controller {args.name} failed: {message}")

    _with_manager(args, load)
    print(
        f"Successfully loaded controller {args.name}"
        + (f" into state {args.set_state}" if args.set_state else "")
    )
    return 0


def _switch(args: argparse.Namespace) -> int:
    strictness = 2 if args.strict else 1
    ok, message = _with_manager(
        args, lambda c: c.switch(args.activate, args.deactivate, strictness)
    )
    if not ok:
        raise RobomodelError(f"switching controllers failed: {message}")
    print("Successfully switched controllers")
    return 0


# ros2controlcli's words: "Successfully cleaned up controller X" (cleanup_controller.py)
_DONE = {"configure": "configured", "cleanup": "cleaned up", "unload": "unloaded"}


def _simple(args: argparse.Namespace) -> int:
    verb = args.service.split("_")[0]
    _check(_with_manager(args, lambda c: getattr(c, verb)(args.name)), f"{verb} of {args.name}")
    print(f"Successfully {_DONE[verb]} controller {args.name}")
    return 0


def _run(args: argparse.Namespace) -> int:
    from robomodel.control import ControlSystem, load_controller_config
    from robomodel.description.urdf.writer import urdf_to_string
    from robomodel.runtime.nodes.robot_state_publisher import RobotStatePublisher

    result, _, _ = load_from_args(args)
    robot = result.robot
    config = load_controller_config(args.controllers)
    with context_from_args(args, announce="robomodel control run") as context:
        system = ControlSystem.build(
            robot,
            config,
            context=context,
            update_rate_hz=args.update_rate,
            spawn=[] if args.inactive or args.no_spawn else None,
        )
        if args.inactive and not args.no_spawn:
            for spec in config.controllers:
                system.manager.load_controller(spec.name)
                system.manager.configure_controller(spec.name)
        RobotStatePublisher(context, urdf_to_string(robot), namespace=config.namespace)
        system.manager.start()
        cm = system.manager.service_prefix
        print(
            f"controller manager {cm} at {system.manager.update_rate_hz} Hz on "
            f"{len(system.resources.components)} hardware component(s); controllers: "
            + ", ".join(f"{c['name']} ({c['state']})" for c in system.manager.list_controllers())
            + f"; bus {context.transport.name}; Ctrl-C stops",
            file=sys.stderr,
        )
        viewer = None if args.no_view else _start_viewer(args)
        try:
            with contextlib.suppress(KeyboardInterrupt):
                context.spin(duration_s=args.duration)
        finally:
            system.manager.shutdown()
            if viewer is not None:
                viewer.close()
    return 0


def _start_viewer(
    args: argparse.Namespace,
    *,
    fixed_frame: str | None = None,
    scenery: tuple[Any, ...] = (),
    sources: list[tuple[str, dict[str, str], str]] | None = None,
) -> Any:
    """Start the browser viewer on the bus if this installation has it (imported lazily).

    The viewer reads /joint_states and /tf from the bus (``external`` joint states), so it needs
    Zenoh. ``fixed_frame`` and ``scenery`` (``SceneryShape``s) are passed on to it; ``sources``
    are the robots as (file, xacro arguments, frame prefix), default the command line's FILE.
    Returns the viewer (to close) or ``None`` when running headless.
    """
    try:
        viewer_module = importlib.import_module("robomodel.viewer")
        Viewer = viewer_module.Viewer
        ViewerOptions = viewer_module.ViewerOptions
        RobotSource = viewer_module.RobotSource
    except (ImportError, AttributeError) as exc:
        reason = "" if isinstance(exc, ModuleNotFoundError) else f" ({exc})"
        print(
            f"robomodel: the viewer is not available in this installation{reason}; running "
            "headless (use --no-view to silence this)",
            file=sys.stderr,
        )
        return None
    if bus_from_args(args) != "zenoh":
        print("robomodel: the viewer needs --bus zenoh; running headless", file=sys.stderr)
        return None
    from robomodel.cli._common import package_index_from_args, split_mappings

    robots = sources or [(args.file, split_mappings(args.mappings), "")]
    try:
        viewer = Viewer(
            ViewerOptions(
                sources=tuple(RobotSource(*source) for source in robots),
                bus="zenoh",
                domain_id=args.domain_id,
                connect=tuple(args.connect),
                listen=tuple(args.listen),
                external=True,
                state_publisher=False,  # this process runs robot_state_publisher itself
                port=args.port,
                package_index=package_index_from_args(args),
                fixed_frame=fixed_frame,
                scenery=scenery,
                frame_rate_hz=args.frame_rate,
            )
        )
        viewer.start()
    except (TypeError, RobomodelError) as exc:
        print(f"robomodel: the viewer could not start ({exc}); running headless", file=sys.stderr)
        return None
    print(f"robomodel {args.verb}: viewer at {viewer.url}", file=sys.stderr)
    if not getattr(args, "no_browser", True):
        webbrowser.open(viewer.url)
    return viewer
