"""``robomodel launch``: run a ROS 1 (roslaunch) or ROS 2 (``ros2 launch``) launch file with
robomodel's components.

``robomodel launch PKG FILE [name:=value ...]`` finds FILE inside package PKG, as roslaunch
and ``ros2 launch`` do; ``robomodel launch PATH [name:=value ...]`` takes the file itself.
ROS 1: ``--dump-params``, ``--nodes``, ``--args NODE``, ``--files`` and ``--ros-args`` print
what roslaunch's flags of the same names print. ROS 2 (``.launch.py``, ROS 2 XML, ``.yaml``):
``--show-args`` and ``--print``/``-p`` as ``ros2 launch``. None of these starts anything.
"""

from __future__ import annotations

import argparse
import os
import re
import sys
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from robomodel.cli._ports import add_port_argument
from robomodel.cli._signals import stop_on_signals
from robomodel.cli._verbs import verb_help
from robomodel.errors import RobomodelError, close_matches

__all__ = ["dialect_of", "register", "run"]


def _domain_id(text: str) -> int:
    from robomodel.cli._bus import domain_id_arg  # the bus's modules load only when used

    return domain_id_arg(text)


def register(subparsers: Any) -> None:
    parser = subparsers.add_parser(
        "launch",
        help=verb_help("launch"),
        description=(
            "Run a ROS 1 launch file as roslaunch does, or a ROS 2 one (.launch.py, XML, YAML) "
            "as ros2 launch does, each node mapped onto a robomodel "
            "component (robot_state_publisher, joint_state_publisher(_gui), rviz -> the browser "
            "viewer, gazebo_ros gzserver/spawn_model -> the simulator, controller_manager "
            "spawner, static_transform_publisher, rqt tools). Arguments: PKG FILE or PATH, then "
            "name:=value launch args."
        ),
    )
    parser.add_argument("inputs", nargs="+", metavar="PKG FILE | PATH [name:=value ...]")
    parser.add_argument(
        "--package-path", action="append", default=[], metavar="DIR",
        help="directory scanned for package.xml, for PKG and $(find pkg) (repeatable)",
    )  # fmt: skip
    parser.add_argument(
        "--package", action="append", default=[], metavar="NAME=DIR",
        help="explicit package location (repeatable)",
    )  # fmt: skip
    _add_show_options(parser)
    _add_run_options(parser)
    parser.set_defaults(func=run)


def _add_show_options(parser: Any) -> None:
    """roslaunch's and ros2 launch's print-and-exit flags (one at a time)."""
    show = parser.add_mutually_exclusive_group()
    show.add_argument("--dump-params", action="store_true", help="print the parameters (YAML)")
    show.add_argument("--nodes", action="store_true", help="print the node names")
    show.add_argument("--args", metavar="NODE", help="print the command line of NODE")
    show.add_argument("--files", action="store_true", help="print the launch files loaded")
    show.add_argument("--ros-args", action="store_true", help="print the launch file's args")
    show.add_argument(
        "-s", "--show-args", "--show-arguments", action="store_true", dest="show_args",
        help="ROS 2: show the launch file's arguments (ros2 launch --show-args)",
    )  # fmt: skip
    show.add_argument(
        "-p", "--print", "--print-description", action="store_true", dest="print_description",
        help="ROS 2: print the launch description (ros2 launch --print)",
    )  # fmt: skip


def _add_run_options(parser: Any) -> None:
    """How the launch runs: viewer, bus, duration, command bounds."""
    parser.add_argument("--headless", action="store_true", help="run no viewer")
    parser.add_argument(
        "--no-browser", action="store_true", help="serve the viewer, open no browser"
    )
    add_port_argument(parser, "the viewer's HTTP port")
    parser.add_argument(
        "--bus", choices=("zenoh", "inproc", "ros1"), default=None,
        help="zenoh (rmw_zenoh's wire: ROS 2 nodes and other robomodel commands see the nodes), "
        "ros1 (a ROS 1 master's graph; the default for ROS 1 launch files when ROS_MASTER_URI "
        "is set or with --ros1-master) or inproc",
    )  # fmt: skip
    parser.add_argument(
        "--ros1-master", nargs="?", const="", default=None, metavar="URI",
        help="ROS 1 launch files: join the ROS 1 master at URI (default ROS_MASTER_URI, else "
        "http://localhost:11311/), or start one there if none answers, as roslaunch does",
    )  # fmt: skip
    parser.add_argument(
        "--domain-id", type=_domain_id, default=None, help="ROS_DOMAIN_ID for zenoh"
    )
    parser.add_argument(
        "--duration", type=float, default=None, metavar="S",
        help="stop after S seconds (for scripts; roslaunch runs until Ctrl-C)",
    )  # fmt: skip
    parser.add_argument(
        "--command-timeout", type=float, default=60.0, metavar="S",
        help="the longest a <param command=...> or $(command ...) may run (default 60 s); "
        "its output is capped at 64 MiB",
    )  # fmt: skip


def _split(inputs: list[str]) -> tuple[list[str], dict[str, str]]:
    files: list[str] = []
    args: dict[str, str] = {}
    for item in inputs:
        if ":=" in item:
            name, _, value = item.partition(":=")
            if not name:
                raise RobomodelError(f"launch argument '{item}' has no name; write name:=value")
            args[name] = value
        else:
            files.append(item)
    return files, args


_LAUNCH_NAME = re.compile(r"\.launch$|[._]launch\.(py|xml|yaml|yml)$|^launch.*\.(py|xml)$")


def _resolve_file(files: list[str], index: Any) -> Path:
    """PATH, or PKG FILE found anywhere in the package (roslaunch's resolve_launch_arguments)."""
    if len(files) == 1:
        path = Path(files[0])
        if not path.exists():
            raise RobomodelError(f"The following input files do not exist: {files[0]}")
        return path
    if len(files) != 2:
        raise RobomodelError(
            f"expected PKG FILE or PATH (then name:=value args), got: {' '.join(files)}"
        )
    package, name = files
    root = index.find(package)
    walk = [(Path(d), names) for d, _subdirs, names in os.walk(root)]
    matches = sorted(d / name for d, names in walk if name in names)
    if not matches:
        launches = sorted({n for _, names in walk for n in names if _LAUNCH_NAME.search(n)})
        hint = close_matches(name, launches)
        mean = f" (did you mean {', '.join(repr(h) for h in hint)}?)" if hint else ""
        raise RobomodelError(
            f"[{name}] is neither a launch file in package [{package}] nor is [{package}] a "
            f"launch file name{mean}; launch files in {package}: {', '.join(launches) or '(none)'}"
        )
    if len(matches) > 1:
        listing = ", ".join(str(m) for m in matches)
        raise RobomodelError(f"multiple files named [{name}] in package [{package}]: {listing}")
    return matches[0]


def _warn_undeclared(path: Path, given: dict[str, str], declared: Sequence[str]) -> None:
    """roslaunch and ros2 launch ignore a ``name:=value`` no ``<arg>`` declares; a typo then
    goes unnoticed, so robomodel warns (and runs on, as they do)."""
    from robomodel.errors import close_matches

    for name in given:
        if name in declared or name.startswith("_"):
            continue
        hint = close_matches(name, declared)
        mean = f" (did you mean {', '.join(repr(h) for h in hint)}?)" if hint else ""
        print(
            f"{path}: warning: launch argument {name}:=... is not declared by the launch file "
            f"and is ignored{mean}; declared arguments: {', '.join(declared) or '(none)'}",
            file=sys.stderr,
        )


def run(args: argparse.Namespace) -> int:
    from robomodel.description.packages import index_from_options
    from robomodel.launch.packages import launch_package_index
    from robomodel.launch.ros1 import (
        format_dump_params,
        format_files,
        format_node_args,
        format_nodes,
        format_ros_args,
        load_launch,
    )

    files, launch_args = _split(args.inputs)
    user_index = index_from_options(args.package_path, args.package)
    if len(files) == 1 and Path(files[0]).exists():
        user_index = user_index.with_workspace_of(files[0])
    path = _resolve_file(files, launch_package_index(user_index))
    if dialect_of(path) == "ros2":
        return _run_ros2(path, launch_args, args, user_index)
    if args.show_args or args.print_description:
        raise RobomodelError(
            f"{path} is a ROS 1 launch file: --show-args and --print are ros2 launch's; "
            "roslaunch's are --ros-args and --nodes/--dump-params"
        )
    launch = load_launch(
        path, args=launch_args, packages=user_index, command_timeout_s=args.command_timeout
    )
    for warning in launch.warnings:
        print(warning, file=sys.stderr)
    _warn_undeclared(path, launch_args, launch.declared_args)
    printed = {
        "dump_params": format_dump_params,
        "nodes": format_nodes,
        "files": format_files,
        "ros_args": format_ros_args,
    }
    for flag, formatter in printed.items():
        if getattr(args, flag):
            sys.stdout.write(formatter(launch))
            return 0
    if args.args:
        sys.stdout.write(format_node_args(launch, args.args, packages=user_index))
        return 0
    return _run(launch, args, user_index)


_ROS2_XML_MARKERS = (b"<let ", b" exec=", b"$(var ", b"$(find-pkg-", b"<push-ros-namespace",
                     b"<push_ros_namespace", b"<set_parameter", b"<set-parameter")  # fmt: skip


def dialect_of(path: Path) -> str:
    """``ros2`` for Python and YAML launch files and ROS 2 XML (``<let>``, ``exec=``,
    ``$(var)``, ...); ``ros1`` for roslaunch XML."""
    name = path.name
    if name.endswith((".py", ".yaml", ".yml")):
        return "ros2"
    if name.endswith(".xml"):
        with open(path, "rb") as handle:  # a regular file: _resolve_file checked it
            head = handle.read(1_000_000)
        if any(marker in head for marker in _ROS2_XML_MARKERS):
            return "ros2"
    return "ros1"


def _run_ros2(path: Path, launch_args: dict[str, str], args: argparse.Namespace, index: Any) -> int:
    from robomodel.launch.packages import launch_package_index
    from robomodel.launch.ros2 import format_print, format_show_args, load_launch

    for flag in ("dump_params", "nodes", "files", "ros_args", "args"):
        if getattr(args, flag):
            raise RobomodelError(
                f"{path} is a ROS 2 launch file: --{flag.replace('_', '-')} is roslaunch's; "
                "ros2 launch has --show-args and --print"
            )
    launch = load_launch(
        path,
        args=launch_args,
        packages=launch_package_index(index),
        command_timeout_s=args.command_timeout,
    )
    try:
        for warning in launch.warnings:
            print(warning, file=sys.stderr)
        _warn_undeclared(path, launch_args, [a.name for a in launch.arguments])
        if args.show_args:
            sys.stdout.write(format_show_args(launch))
            return 0
        if args.print_description:
            sys.stdout.write(format_print(launch))
            return 0
        return _run_ros2_nodes(launch, args, index)
    finally:
        launch.remove_temporary_files()


def _run_ros2_nodes(launch: Any, args: argparse.Namespace, index: Any) -> int:
    from robomodel.launch.runner import LaunchRunner

    nodes = [step.node for step in launch.steps if step.node is not None]
    runner = LaunchRunner(nodes, _options(args, index, path=launch.path), steps=launch.steps)
    runner.check()
    # Ctrl-C and SIGTERM are a flag from here on: one that came while the nodes started
    # would otherwise raise inside a node's start-up and could leave a lock held.
    with stop_on_signals() as stopped:
        runner.open_bus()
        try:
            runner.start_nodes()
            print(f"[launch] {launch.path}: {len(runner.started)} nodes running", file=sys.stderr)
            return runner.spin(stopped)
        finally:
            runner.shutdown()


def _options(
    args: argparse.Namespace, index: Any, *, ros1_launch: bool = False, path: Any = None
) -> Any:
    from robomodel.launch.runner import RunOptions

    return RunOptions(
        bus=_bus(args, ros1_launch),
        master_uri=args.ros1_master or None,
        domain_id=args.domain_id,
        headless=args.headless,
        open_browser=not args.no_browser,
        port=args.port,
        duration_s=args.duration,
        package_index=index,
        launch_file=str(path) if path is not None else None,
    )


def _bus(args: argparse.Namespace, ros1_launch: bool) -> str:
    """The bus asked for; by default ros1 for a ROS 1 launch file when a ROS 1 master is wanted
    (ROS_MASTER_URI set, or --ros1-master), zenoh otherwise."""
    if args.bus is not None:
        return str(args.bus)
    wanted = args.ros1_master is not None or bool(os.environ.get("ROS_MASTER_URI"))
    return "ros1" if ros1_launch and wanted else "zenoh"


def _run(launch: Any, args: argparse.Namespace, index: Any) -> int:
    from robomodel.launch.runner import LaunchRunner

    runner = LaunchRunner(launch.nodes, _options(args, index, ros1_launch=True, path=launch.path))
    runner.check()
    own = runner.user_nodes()
    if own and runner.options.bus != "ros1":
        if args.bus is None:
            # rospy nodes find their parameters and peers through a master: roslaunch's roscore
            from dataclasses import replace

            runner.options = replace(runner.options, bus="ros1")
        else:
            names = ", ".join(spec.fqn for spec in own)
            print(
                f"{launch.path}: warning: {names} run as your own ROS 1 nodes, which find "
                f"their parameters and peers through a ROS 1 master; on --bus {args.bus} they "
                "do not see the launch's (leave out --bus, or use --bus ros1)",
                file=sys.stderr,
            )
    # Ctrl-C and SIGTERM are a flag from here on: one that came while the nodes started
    # would otherwise raise inside a node's start-up and could leave a lock held.
    with stop_on_signals() as stopped:
        runner.open_bus()
        try:
            runner.set_params(
                dict(launch.params),
                clear=launch.clear_params,
                deletes=launch.param_deletes,
                dumps=launch.param_dumps,
            )
            runner.start_nodes()
            print(f"[launch] {launch.path}: {len(runner.started)} nodes running", file=sys.stderr)
            return runner.spin(stopped)
        finally:
            runner.shutdown()
