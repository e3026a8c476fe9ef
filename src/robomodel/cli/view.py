"""``robomodel view``: RViz (RobotModel + TF) and joint_state_publisher_gui in the browser.

``robomodel view FILE [FILE ...] [name:=value ...] [--prefix P ...]`` expands each
description, runs robot_state_publisher and joint_state_publisher for it, serves the page on
loopback, prints the URL and opens a browser; saving a file reloads it in the page. Without a
FILE the page starts as RViz does, with no robot: the RobotModel displays of the config (or
those added in the page) bring them; ``--description-topic TOPIC`` (repeatable) draws the robot
another process describes there.
``-d FILE.rviz`` opens an RViz config (a missing one: RViz's defaults and one warning line);
the page's File folder saves it.
"""

from __future__ import annotations

import argparse
import contextlib
import sys
import threading
import time
import webbrowser
from typing import TYPE_CHECKING, Any

from robomodel._watchdog import ends_process_after
from robomodel.cli._bus import add_bus_arguments
from robomodel.cli._common import (
    add_frame_rate_argument,
    add_package_options,
    package_index_from_args,
    split_inputs,
)
from robomodel.cli._ports import add_port_argument
from robomodel.cli._verbs import verb_help
from robomodel.errors import RobomodelError

if TYPE_CHECKING:
    from robomodel.viewer import RobotSource

__all__ = ["register"]


def register(subparsers: Any) -> None:
    parser = subparsers.add_parser(
        "view",
        help=verb_help("view"),
        description=(
            "Serve a web page showing the robots (RViz's RobotModel and TF displays) with "
            "joint sliders (joint_state_publisher_gui); reloads when a file is saved."
        ),
    )
    _add_description_arguments(parser)
    _add_page_arguments(parser)
    add_package_options(parser, mappings=False)
    parser.add_argument(
        "--duration", type=float, default=None, help=argparse.SUPPRESS
    )  # stop after S seconds (tests, benchmarks)
    add_bus_arguments(parser, default="inproc")
    parser.set_defaults(func=run)


def _add_description_arguments(parser: argparse.ArgumentParser) -> None:
    """What to draw: the FILEs with their xacro arguments and prefixes, or a topic."""
    parser.add_argument(
        "inputs",
        nargs="*",
        metavar="FILE|name:=value",
        help=".urdf or .xacro files, and xacro arguments name:=value (for every file); none "
        "with --joint-states external: the description another process publishes",
    )
    parser.add_argument(
        "--description-topic",
        action="append",
        default=[],
        metavar="TOPIC",
        help="draw the robot described on TOPIC (RViz's RobotModel with Description Source "
        "Topic; repeatable, one robot each). Without FILE or TOPIC the page starts with no "
        "robot, as RViz does: the -d config's RobotModel displays (RViz's defaults: one on "
        "/robot_description) bring them",
    )
    parser.add_argument(
        "--prefix",
        action="append",
        default=[],
        metavar="P",
        help="frame prefix of each FILE, then of each --description-topic's robot (its "
        "RobotModel's TF Prefix), in order (repeatable; verbatim, e.g. robot1/)",
    )


def _add_page_arguments(parser: argparse.ArgumentParser) -> None:
    """How the page is served and what it shows beside the robots."""
    add_port_argument(parser, "HTTP port")
    parser.add_argument(
        "--host", default="127.0.0.1", help="address to serve on (default: 127.0.0.1)"
    )
    parser.add_argument("--no-browser", action="store_true", help="do not open a browser")
    parser.add_argument(
        "--fixed-frame", default=None, metavar="LINK", help="fixed frame (default: root link)"
    )
    parser.add_argument(
        "-d",
        "--display-config",
        default=None,
        metavar="FILE.rviz",
        help="RViz config to open (rviz -d): Fixed Frame, RobotModel, TF, Grid, the view; "
        "a FILE that does not exist yet opens RViz's defaults, and the page's Save Config "
        "writes it",
    )
    parser.add_argument(
        "--joint-states",
        choices=("sliders", "external"),
        default="sliders",
        help="sliders (joint_state_publisher_gui) or external (/joint_states, /tf from the bus)",
    )
    add_frame_rate_argument(parser)
    parser.add_argument(
        "--no-tools",
        action="store_true",
        help="hide the rqt tools (robot steering, plot, topic publisher, parameters) and add no "
        "displays for the graph's scans and odometry",
    )


def _report_meshes(viewer: Any) -> None:
    """Say on stderr when every mesh is in the scene (the page is served before that)."""
    started = time.monotonic()

    def report() -> None:
        viewer.meshes_ready.wait()
        count = viewer.meshes.loads
        elapsed = time.monotonic() - started
        print(
            f"robomodel view: scene ready ({count} mesh files loaded in {elapsed:.2f} s)",
            file=sys.stderr,
            flush=True,
        )

    threading.Thread(target=report, daemon=True).start()


def _rviz_document(args: argparse.Namespace) -> Any:
    """The -d config (None without -d); a missing file is one warning line on stderr."""
    if args.display_config is None:
        return None
    from robomodel.viewer.rviz_document import open_rviz_document
    from robomodel.viewer.rviz_model import RvizDialect

    dialect = RvizDialect.ROS1 if args.bus == "ros1" else RvizDialect.ROS2
    document, warning = open_rviz_document(args.display_config, dialect)
    if warning is not None:
        print(f"robomodel view: warning: {warning}", file=sys.stderr, flush=True)
    return document


def _checked_inputs(
    args: argparse.Namespace,
) -> tuple[list[str], dict[str, str], list[str]]:
    """The FILEs, their xacro arguments and the description topics, checked against the
    options that go with them. No FILE and no topic is RViz's empty start: the config's
    RobotModel displays (RViz's defaults: one on /robot_description), or one added in the
    page, bring the robots."""
    inputs = list(args.inputs)
    files = [item for item in inputs if ":=" not in item]
    if files:
        files, mappings = split_inputs(inputs, "view")
    elif inputs:
        raise RobomodelError(
            f"xacro arguments ({', '.join(inputs)}) without a FILE: give the .urdf or .xacro file"
        )
    else:
        mappings = {}
    topics = list(args.description_topic)
    if len(args.prefix) > len(files) + len(topics):
        raise RobomodelError(
            f"{len(args.prefix)} --prefix options for {len(files)} file(s) and "
            f"{len(topics)} --description-topic(s); give one per FILE, then per topic"
        )
    if args.joint_states == "external" and args.bus not in ("zenoh", "ros1"):
        raise RobomodelError(
            "--joint-states external reads /joint_states and /tf from other processes: "
            "add --bus zenoh (ROS 2, robomodel) or --bus ros1 (a ROS 1 master)"
        )
    if topics and args.bus not in ("zenoh", "ros1"):
        raise RobomodelError(
            "a description from a topic comes from another process, with its /tf: "
            "add --bus zenoh (ROS 2, robomodel) or --bus ros1 (a ROS 1 master)"
        )
    return files, mappings, topics


def _robot_sources(
    args: argparse.Namespace, files: list[str], mappings: dict[str, str], topics: list[str]
) -> tuple[RobotSource, ...]:
    """One :class:`~robomodel.viewer.RobotSource` per FILE, then one per topic, each with its
    ``--prefix`` in order: a FILE's frame_prefix, a topic's TF Prefix (the prefix its
    robot_state_publisher gives the frames, as RViz's RobotModel is told)."""
    from robomodel.viewer import RobotSource

    count = len(files) + len(topics)
    prefixes = [*args.prefix, *([""] * (count - len(args.prefix)))]
    sources = [RobotSource(f, mappings, p) for f, p in zip(files, prefixes, strict=False)]
    for topic, prefix in zip(topics, prefixes[len(files) :], strict=True):
        sources.append(RobotSource("", {}, prefix, topic="/" + topic.strip().lstrip("/")))
    return tuple(sources)


def _announce(viewer: Any) -> None:
    """Print the page's URL, the bus (stderr) and why a robot did not load (stderr)."""
    print(f"robomodel view: serving {viewer.url} (Ctrl-C stops)", flush=True)
    context = getattr(viewer, "context", None)
    if context is not None:
        print(f"robomodel view: {context.transport.describe()}", file=sys.stderr, flush=True)
    for session in viewer.sessions:
        if session.failure is not None:
            for line in session.failure.message.splitlines() + [
                d.format() for d in session.failure.diagnostics[1:]
            ]:
                print(f"robomodel view: {line}", file=sys.stderr, flush=True)


def run(args: argparse.Namespace) -> int:
    from robomodel.viewer import Viewer, ViewerOptions

    files, mappings, topics = _checked_inputs(args)
    document = _rviz_document(args)
    options = ViewerOptions(
        sources=_robot_sources(args, files, mappings, topics),
        host=args.host,
        port=args.port,
        fixed_frame=args.fixed_frame,
        bus=args.bus,
        master=args.master,
        domain_id=args.domain_id,
        connect=tuple(args.connect),
        listen=tuple(args.listen),
        external=args.joint_states == "external",
        package_index=package_index_from_args(args),
        tools=not args.no_tools,
        frame_rate_hz=args.frame_rate,
        rviz=document,
    )
    viewer = Viewer(options)
    try:
        viewer.start()
        _announce(viewer)
        if not options.sources:
            where = (
                "no other process can describe one on --bus inproc: a RobotModel display with "
                "Description Source File loads a file"
                if args.bus == "inproc"
                else "its RobotModel displays load those other processes describe"
            )
            print(f"robomodel view: no FILE: the page starts with no robot; {where}",
                  file=sys.stderr, flush=True)  # fmt: skip
        _report_meshes(viewer)
        if not args.no_browser:
            webbrowser.open(viewer.url)
        with contextlib.suppress(KeyboardInterrupt):
            viewer.wait(args.duration)
    finally:
        _close_within(viewer, CLOSE_BOUND_S)
    return 0


CLOSE_BOUND_S = 30.0
"""How long Ctrl-C waits for the viewer to let go of its page, bus and threads."""


def _close_within(viewer: Any, bound_s: float) -> None:
    """``viewer.close()``, bounded: past ``bound_s`` the threads' stacks go to stderr and the
    process ends with 130, so that Ctrl-C always ends the viewer (it starts no processes, so
    nothing is left behind)."""
    with ends_process_after(
        bound_s, f"robomodel view: did not stop within {bound_s:g} s; ending now", exit_code=130
    ):
        viewer.close()
