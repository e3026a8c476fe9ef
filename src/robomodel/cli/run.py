"""``robomodel run PKG EXECUTABLE [ARGS...]``: one node, as ``rosrun`` and ``ros2 run`` start it.

A package and executable robomodel maps (the registry of :mod:`robomodel.launch.nodes`) runs
that component, started by the runner ``robomodel launch`` uses, so a command line and a launch
file's ``<node>`` behave alike; robomodel's names keep that priority. Any other executable is the
user's own node (an rclpy or rospy program), found on the package path as ``ros2 run`` and
``rosrun`` find it (:mod:`robomodel.launch.executables`: ``console_scripts``, ``lib/PKG/EXEC``,
a file of the package) and run with robomodel's Python in the foreground, its arguments passed
through unchanged. A C++ node is refused in one line. Its arguments are ROS 1's (``__name:=``, ``__ns:=``,
``_param:=value``, ``from:=to``) on a ROS 1 master, ROS 2's (``--ros-args -r ... -p ...
--params-file ...``) on Zenoh (:mod:`robomodel.launch.node_args`).

The bus is the other verbs' (a ROS 1 master when ROS_MASTER_URI is set, else Zenoh). A ROS 1
node needs a running master, as rosrun's do. The command ends when the node ends (its exit
code) or on Ctrl-C / SIGTERM.
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from typing import Any, NoReturn

from robomodel.cli._bus import add_bus_arguments, bus_from_args
from robomodel.cli._ports import add_port_argument
from robomodel.cli._signals import stop_on_signals
from robomodel.cli._verbs import verb_help
from robomodel.errors import RobomodelError, describe_unknown

__all__ = ["register", "run"]


def register(subparsers: Any) -> None:
    parser = subparsers.add_parser(
        "run",
        help=verb_help("run"),
        description=(
            "Run one node as rosrun / ros2 run do: the component robomodel launch maps "
            "PKG/EXECUTABLE onto, or else your own package's executable (an rclpy or rospy "
            "program: a console_scripts entry of setup.py, lib/PKG/EXECUTABLE of an install "
            "prefix, or a file of the package, found on the package path) in the foreground "
            "with robomodel's Python. Options of robomodel come before PKG; everything after "
            "EXECUTABLE is the node's (ROS 1: __name:=, __ns:=, _param:=value, from:=to; ROS 2: "
            "--ros-args -r from:=to -r __ns:=/x -r __node:=n -p name:=value --params-file F)."
        ),
    )
    parser.add_argument(
        "--package-path", action="append", default=[], metavar="DIR",
        help="directory scanned for package.xml, for PKG (repeatable; a workspace's src/ is "
        "enough)",
    )  # fmt: skip
    parser.add_argument(
        "--package", action="append", default=[], metavar="NAME=DIR", dest="package_option",
        help="explicit package location (repeatable)",
    )  # fmt: skip
    parser.add_argument("package", metavar="PKG")
    parser.add_argument("executable", metavar="EXECUTABLE")
    parser.add_argument("arguments", nargs=argparse.REMAINDER, metavar="ARGS")
    parser.add_argument("--headless", action="store_true", help="rviz: run no viewer")
    parser.add_argument(
        "--no-browser", action="store_true", help="rviz: serve the viewer, open no browser"
    )
    add_port_argument(parser, "rviz: the viewer's HTTP port")
    add_bus_arguments(parser)
    parser.set_defaults(func=run)


def _mapped(package: str, executable: str) -> set[str]:
    """The dialects in which robomodel maps ``package``/``executable`` onto a component."""
    from robomodel.launch.nodes import supported

    return {d for d in ("ros1", "ros2") if (package, executable) in _executables(supported(d))}


def _dialect(package: str, executable: str, ros1_bus: bool) -> str:
    """ROS 1's node on a ROS 1 master, else ROS 2's where robomodel has one, else ROS 1's."""
    known = _mapped(package, executable)
    if ros1_bus and "ros1" in known:
        return "ros1"
    return "ros2" if "ros2" in known else "ros1"


def _executables(rows: list[tuple[str, str, str]]) -> set[tuple[str, str]]:
    return {(package, executable) for package, executable, _ in rows}


def _mapped_executables() -> set[tuple[str, str]]:
    """Every ``(package, executable)`` robomodel maps onto a component, in either dialect."""
    from robomodel.launch.nodes import supported

    return _executables(supported("ros1")) | _executables(supported("ros2"))


def _refuse(package: str, executable: str, index: Any) -> NoReturn:
    """One line: the unknown package or executable, a did-you-mean, what there is."""
    known = _mapped_executables()
    # example-robot-data's descriptions hold no nodes: they would drown the close names
    users = {n for n in index.names() if index.get(n).origin != "example-robot-data"}
    packages = sorted({p for p, _ in known} | users)
    if package not in packages:
        searched = "; ".join(index.searched) or "no package path given"
        raise RobomodelError(
            describe_unknown("robomodel run: unknown package", package, packages, "packages are")
            + f" (searched: {searched}; add your workspace with --package-path DIR)"
        )
    executables = sorted({e for p, e in known if p == package})
    raise RobomodelError(
        describe_unknown(
            f"robomodel run: package '{package}' has no executable",
            executable,
            executables,
            f"{package}'s executables are",
        )
    )


# The ROS 1 nodes that pick an anonymous name (ros::init_options::AnonymousName, rospy's
# anonymous=True), so that two of them can run at once: tf2_ros's and tf's
# static_transform_publisher, tf_echo, tf2_echo, tf's view_frames, rviz, controller_manager's
# scripts.
_ANONYMOUS_ROS1 = {
    ("tf2_ros", "static_transform_publisher"), ("tf", "static_transform_publisher"),
    ("tf", "tf_echo"), ("tf2_ros", "tf2_echo"), ("tf", "view_frames"), ("rviz", "rviz"),
    ("controller_manager", "controller_manager"), ("controller_manager", "spawner"),
    ("controller_manager", "unspawner"),
}  # fmt: skip


def _default_name(package: str, executable: str, dialect: str) -> str | None:
    """The name the node gives itself: ROS 2's executables pick their own (None)."""
    if dialect != "ros1":
        return None
    if (package, executable) in _ANONYMOUS_ROS1:
        return f"{executable}_{os.getpid()}_{int(time.time() * 1000)}"  # rospy's form
    return executable


def _spec(args: argparse.Namespace, dialect: str) -> tuple[Any, dict[str, Any], str | None]:
    """The node's NodeSpec, its ROS 1 private parameters (full names), its ROS 1 master."""
    from robomodel.launch.model import NodeSpec, ParamSource
    from robomodel.launch.node_args import parse_ros1_args, parse_ros2_args

    if dialect == "ros1":
        parsed = parse_ros1_args(args.arguments)
    else:
        parsed = parse_ros2_args(args.arguments, default_name=args.executable)
    namespace = parsed.namespace or os.environ.get("ROS_NAMESPACE") or "/"
    namespace = "/" + namespace.strip("/") + "/" if namespace.strip("/") else "/"
    sources: tuple[ParamSource, ...] = ()
    if dialect == "ros2":
        sources = tuple(ParamSource(file=f.resolve()) for f in parsed.params_files)
        for path in parsed.params_files:
            if not path.is_file():
                raise RobomodelError(f"--params-file {path}: no such file")
        if parsed.params:
            sources += (ParamSource(values=dict(parsed.params)),)
    spec = NodeSpec(
        dialect,  # type: ignore[arg-type]
        args.package,
        args.executable,
        parsed.name or _default_name(args.package, args.executable, dialect),
        namespace=namespace,
        args=parsed.args,
        remaps=parsed.remaps,
        parameters=sources,
        required=True,  # the command ends with its node
        output="screen",
    )
    private = {}
    if dialect == "ros1":
        private = {f"{spec.fqn}/{name}": value for name, value in parsed.params.items()}
    return spec, private, parsed.master


def _quiet(text: str) -> None:
    """The runner's log without its launch chatter (rosrun prints none of it)."""
    chatter = ("started ", "parameter server ", "required node ", "ROS 1 master at ")
    if text.startswith(tuple(f"[launch] {words}" for words in chatter)):
        return
    print(text, file=sys.stderr, flush=True)


def _run_user_node(args: argparse.Namespace, index: Any) -> int:
    """The user's own executable ``PKG EXECUTABLE``, in the foreground; its exit code."""
    from robomodel.errors import PackageNotFoundError
    from robomodel.launch.executables import ExecutableNotFoundError, find_executable
    from robomodel.launch.user_nodes import run_foreground

    try:
        package = index.get(args.package)
    except PackageNotFoundError:
        _refuse(args.package, args.executable, index)
    try:
        found = find_executable(args.package, args.executable, package.path)
    except ExecutableNotFoundError as exc:
        # a package robomodel maps (tf2_ros) that is also on the package path (a ROS 1
        # install's): robomodel's executables of it are among the names to suggest
        mapped = {e for p, e in _mapped_executables() if p == args.package}
        if not mapped:
            raise
        raise RobomodelError(
            describe_unknown(
                f"robomodel run: package '{args.package}' has no executable",
                args.executable,
                sorted(mapped | set(exc.available)),
                f"{args.package}'s executables are",
            )
        ) from None
    if args.connect or args.listen:
        raise RobomodelError(
            f"robomodel run: --connect and --listen set up robomodel's own nodes' Zenoh session; "
            f"{args.package}/{args.executable} is your own node, which joins the graph as its "
            "client library does (ROS_DOMAIN_ID, --domain-id)"
        )
    env = dict(os.environ)
    env["ROBOMODEL_MESSAGE_FLAVOUR"] = found.flavour
    if found.source_dir is not None:
        env["PYTHONPATH"] = os.pathsep.join(
            p for p in (str(found.source_dir), env.get("PYTHONPATH", "")) if p
        )
    if args.master:
        env["ROS_MASTER_URI"] = args.master
    if args.domain_id is not None:
        env["ROS_DOMAIN_ID"] = str(args.domain_id)
    return run_foreground([*found.command(), *args.arguments], env)


def run(args: argparse.Namespace) -> int:
    from robomodel.description.packages import index_from_options

    if not _mapped(args.package, args.executable):
        index = index_from_options(args.package_path, args.package_option)
        mapped_packages = {p for p, _ in _mapped_executables()}
        if args.package in mapped_packages and args.package not in index.names():
            _refuse(args.package, args.executable, index)
        return _run_user_node(args, index)
    from robomodel.launch.runner import LaunchRunner, RunOptions

    ros1_bus = bus_from_args(args) == "ros1"
    dialect = _dialect(args.package, args.executable, ros1_bus)
    spec, private, master = _spec(args, dialect)
    bus = "ros1" if (ros1_bus or master) else (args.bus or "zenoh")
    if bus == "ros1":
        _require_master(master or args.master)
    options = RunOptions(
        bus=bus,
        master_uri=master or args.master,
        domain_id=args.domain_id,
        headless=args.headless,
        open_browser=not args.no_browser,
        port=args.port,
        strict_start=True,
        connect=tuple(args.connect),
        listen=tuple(args.listen),
    )
    runner = LaunchRunner([spec], options, log=_quiet)
    # Ctrl-C and SIGTERM are a flag from the start, as for a launch (cli/launch.py)
    with stop_on_signals() as stopped:
        runner.open_bus()
        try:
            if private:
                runner.set_params(private)
            runner.start_nodes()
            runner.spin(stopped)
            code = runner.started[0].handle.exit_code() if runner.started else 1
            return 0 if code is None else int(code)
        finally:
            runner.shutdown()


def _require_master(uri: str | None) -> None:
    from robomodel.runtime.transport.ros1.master import master_answers
    from robomodel.runtime.transport.ros1.names import master_uri

    found = master_uri(uri)
    if not master_answers(found):
        raise RobomodelError(
            f"no ROS 1 master answers at {found}: start one first (robomodel master, or "
            "roscore), or unset ROS_MASTER_URI to run on Zenoh"
        )
