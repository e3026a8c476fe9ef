"""``robomodel log``: the nodes' log lines from ``/rosout``, as rqt_console shows them.

One line per record with rqt_console's columns (time, severity, node, message, location
``file:line``), from any node on the bus: ``rcl_interfaces/msg/Log`` on ROS 2 (levels 10 to 50,
subscribed transient local as rcl publishes it, so lines a node logged before this command
started come too) and ``rosgraph_msgs/Log`` on ROS 1 (levels 1 to 16). Names and messages come
from other processes and are printed with control characters escaped, so a multi-line message
stays one line. Runs until Ctrl-C or SIGTERM (or ``--count`` lines, ``--timeout`` seconds).
"""

from __future__ import annotations

import argparse
import fnmatch
import sys
from dataclasses import dataclass
from typing import Any

from robomodel._escape import escape_name
from robomodel.cli._bus import add_bus_arguments, context_from_args, wait_for_peers
from robomodel.cli._signals import stop_on_signals
from robomodel.cli._verbs import verb_help
from robomodel.errors import RobomodelError

__all__ = [
    "MAX_MESSAGE_CHARS",
    "MAX_NAME_CHARS",
    "MAX_NODE_COLUMN",
    "LogLine",
    "format_line",
    "register",
]

# A peer chooses its log lines: one of megabytes, or a node name that long, would be printed
# whole (and the name would pad every later line to its width). Past these the text is cut and
# says how long it was.
MAX_MESSAGE_CHARS = 8_192  # of one message, and of its file name
MAX_NAME_CHARS = 256  # of a node name
MAX_NODE_COLUMN = 48  # the node column pads to at most this width

# rqt_console's severities; ROS 2's rcl_interfaces/msg/Log levels and ROS 1's rosgraph_msgs/Log.
SEVERITIES = ("debug", "info", "warn", "error", "fatal")
_ROS2_LEVELS = {10: "debug", 20: "info", 30: "warn", 40: "error", 50: "fatal"}
_ROS1_LEVELS = {1: "debug", 2: "info", 4: "warn", 8: "error", 16: "fatal"}


def register(subparsers: Any) -> None:
    p = subparsers.add_parser(
        "log",
        help=verb_help("log"),
        description="Print the log lines every node publishes on /rosout, one per line: time, "
        "severity, node, message, file:line (rqt_console's columns).",
    )
    p.add_argument(
        "--node",
        action="append",
        default=[],
        metavar="GLOB",
        help="only lines of nodes whose name matches GLOB (repeatable; e.g. '/robot_*'; "
        "ROS 2 logger names such as ns.talker also match as /ns/talker)",
    )
    p.add_argument(
        "--level",
        choices=SEVERITIES,
        default="debug",
        help="only lines of this severity and above (default: debug, every line)",
    )
    p.add_argument("-n", "--count", type=int, default=None, help="stop after N lines")
    p.add_argument("--timeout", type=float, default=None, metavar="S", help="stop after S s")
    add_bus_arguments(p)
    p.set_defaults(func=run_log)


@dataclass(frozen=True, slots=True)
class LogLine:
    """One /rosout record, whichever bus it came from."""

    stamp_ns: int
    severity: str  # one of SEVERITIES, or the number a peer sent when it is none of them
    node: str
    message: str
    file: str
    line: int


def _from_message(msg: Any, ros1: bool) -> LogLine:
    levels = _ROS1_LEVELS if ros1 else _ROS2_LEVELS
    stamp = msg.header.stamp if ros1 else msg.stamp
    stamp_ns = int(stamp.sec) * 1_000_000_000 + int(stamp.nanosec)
    severity = levels.get(int(msg.level), str(int(msg.level)))
    return LogLine(stamp_ns, severity, msg.name, msg.msg, msg.file, int(msg.line))


def _node_forms(name: str) -> tuple[str, ...]:
    """The name as sent, and as a node path (rcl's logger ``ns.talker`` is node /ns/talker)."""
    path = "/" + name.lstrip("/").replace(".", "/")
    return (name, path) if path != name else (name,)


def matches(line: LogLine, globs: list[str], level: str) -> bool:
    """Whether ``line`` passes the ``--node`` globs and the ``--level`` minimum."""
    if line.severity in SEVERITIES and SEVERITIES.index(line.severity) < SEVERITIES.index(level):
        return False
    if not globs:
        return True
    return any(fnmatch.fnmatchcase(form, g) for form in _node_forms(line.node) for g in globs)


def _clipped(text: str, limit: int) -> str:
    """``text`` escaped, cut at ``limit`` characters with how long it was."""
    if len(text) <= limit:
        return escape_name(text)
    return f"{escape_name(text[:limit])}… ({len(text)} characters)"


def format_line(line: LogLine, node_width: int = 0) -> str:
    """``sec.nanosec  SEVERITY  node  message  file:line``, text from peers escaped and cut
    at ``MAX_MESSAGE_CHARS`` (``MAX_NAME_CHARS`` for the node)."""
    stamp = f"{line.stamp_ns // 1_000_000_000}.{line.stamp_ns % 1_000_000_000:09d}"
    location = f"  {_clipped(line.file, MAX_MESSAGE_CHARS)}:{line.line}" if line.file else ""
    node = _clipped(line.node, MAX_NAME_CHARS).ljust(min(node_width, MAX_NODE_COLUMN))
    message = _clipped(line.message, MAX_MESSAGE_CHARS)
    return f"{stamp}  {line.severity.upper():<5}  {node}  {message}{location}"


def run_log(args: argparse.Namespace) -> int:
    from robomodel.runtime.rosout import ROSOUT_QOS

    if args.count is not None and args.count < 1:
        raise RobomodelError(f"--count {args.count}: give a positive number of lines, e.g. -n 10")
    printed = [0]
    width = [0]
    with stop_on_signals() as stopped, context_from_args(args, announce="robomodel log") as ctx:
        ros1 = ctx.bus == "ros1"
        if ros1:
            from robomodel.runtime.msg.types.rosgraph_msgs import Log as kind
        else:
            from robomodel.runtime.msg.types.rcl_interfaces import Log as kind  # type: ignore[assignment]
        wait_for_peers(ctx)
        node = ctx.create_node("robomodel_log", enable_rosout=False)

        def show(msg: Any) -> None:
            line = _from_message(msg, ros1)
            if (args.count is not None and printed[0] >= args.count) or not matches(
                line, args.node, args.level
            ):
                return
            width[0] = min(max(width[0], len(escape_name(line.node))), MAX_NODE_COLUMN)
            sys.stdout.write(format_line(line, width[0]) + "\n")
            sys.stdout.flush()
            printed[0] += 1

        node.create_subscription(kind, "/rosout", show, 100 if ros1 else ROSOUT_QOS)
        ctx.spin(
            duration_s=args.timeout,
            until=lambda: stopped() or (args.count is not None and printed[0] >= args.count),
        )
    return 0
