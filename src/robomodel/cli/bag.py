"""``robomodel bag``: record, info and play, with ``ros2 bag``'s options and output."""

from __future__ import annotations

import argparse
import datetime
import logging
import math
import sys
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

from robomodel.cli._bus import add_bus_arguments, context_from_args, wait_for_peers
from robomodel.cli._signals import stop_on_signals
from robomodel.cli._types import add_type_arguments
from robomodel.cli._verbs import verb_help
from robomodel.errors import RobomodelError

__all__ = ["register"]

EXIT_DAMAGED = 2


def register(subparsers: Any) -> None:
    parser = subparsers.add_parser("bag", help=verb_help("bag"))
    verbs = parser.add_subparsers(dest="bag_verb", metavar="VERB")
    verbs.required = True

    p = verbs.add_parser("record", help="record topics to a bag (ros2 bag record)")
    p.add_argument("topics", nargs="*", metavar="TOPIC", help="topics to record")
    p.add_argument("-a", "--all", action="store_true", help="record every topic")
    p.add_argument(
        "--include-hidden-topics",
        action="store_true",
        help="with -a, also hidden topics (a part starting with _, e.g. an action's feedback)",
    )
    p.add_argument("-o", "--output", help="output folder (default: rosbag2_YYYY_MM_DD-HH_MM_SS)")
    p.add_argument("-s", "--storage", choices=("mcap", "sqlite3"), default="mcap")
    p.add_argument("--ros1", metavar="FILE.bag", help="write a ROS 1 bag instead")
    p.add_argument("-b", "--max-bag-size", type=int, default=None, metavar="BYTES")
    p.add_argument("-d", "--max-bag-duration", type=float, default=None, metavar="S")
    p.add_argument("--duration", type=float, default=None, metavar="S", help="stop after S s")
    p.add_argument("--no-progress", action="store_true", help="no progress line")
    add_bus_arguments(p)
    add_type_arguments(p)
    p.set_defaults(func=run_record)

    p = verbs.add_parser("info", help="topics, types, counts and duration of a bag")
    p.add_argument("bag", help="a rosbag2 folder, an .mcap or a ROS 1 .bag file")
    p.set_defaults(func=run_info)

    p = verbs.add_parser("play", help="publish a bag's messages with their timing")
    p.add_argument("bag")
    p.add_argument("-r", "--rate", type=float, default=1.0, help="speed factor (default 1)")
    p.add_argument("-l", "--loop", action="store_true", help="play again and again")
    p.add_argument("--topics", nargs="+", default=None, metavar="TOPIC")
    p.add_argument(
        "-d", "--delay", type=float, default=0.5, metavar="S",
        help="wait S s before the first message, for subscribers to match (default 0.5)",
    )  # fmt: skip
    p.add_argument(
        "--clock", nargs="?", type=float, const=40.0, default=None, metavar="HZ",
        help="publish /clock at HZ (default 40) with the bag's time",
    )  # fmt: skip
    add_bus_arguments(p)
    add_type_arguments(p)
    p.set_defaults(func=run_play)


def _human_size(size: float) -> str:
    for unit in ("B", "KiB", "MiB", "GiB"):
        if size < 1024 or unit == "GiB":
            return f"{size:.1f} {unit}" if unit != "B" else f"{int(size)} B"
        size /= 1024
    return f"{size:.1f} GiB"


def _split_policy(args: argparse.Namespace) -> Any:
    """``-b``/``-d`` as ``ros2 bag record`` takes them: 0 (the default) is no splitting."""
    from robomodel.bag import SplitPolicy

    limits = {"--max-bag-size": args.max_bag_size, "--max-bag-duration": args.max_bag_duration}
    for option, value in limits.items():
        if value is not None and not 0 <= value < math.inf:
            raise RobomodelError(f"{option} must be 0 (no splitting) or positive, got {value}")
    duration_ns = int(args.max_bag_duration * 1e9) if args.max_bag_duration else None
    split = SplitPolicy(args.max_bag_size or None, duration_ns or None)
    if split.splits and args.storage == "sqlite3" and not args.ros1:
        raise RobomodelError("--max-bag-size and --max-bag-duration need --storage mcap")
    return split


def _writer(args: argparse.Namespace, split: Any) -> Any:
    from robomodel.bag import McapFolderWriter, Ros1BagWriter, Sqlite3FolderWriter

    if args.ros1:
        return Ros1BagWriter(Path(args.ros1), split=split)
    stamp = datetime.datetime.now().strftime("%Y_%m_%d-%H_%M_%S")
    folder = Path(args.output or f"rosbag2_{stamp}")
    if args.storage == "sqlite3":
        return Sqlite3FolderWriter(folder, split=split)
    return McapFolderWriter(folder, split=split)


def run_record(args: argparse.Namespace) -> int:
    from robomodel.bag import Recorder

    if not args.all and not args.topics:
        raise RobomodelError("name the topics to record, or -a for all of them")
    split = _split_policy(args)
    logging.basicConfig(format="robomodel bag: %(message)s")
    with (
        stop_on_signals() as stopped,
        context_from_args(args, announce="robomodel bag record") as context,
    ):
        wait_for_peers(context)
        writer = _writer(args, split)
        recorder = Recorder(
            context,
            writer,
            topics=None if args.all else args.topics,
            include_hidden=args.include_hidden_topics,
        )
        try:
            _record_loop(recorder, stopped, args)
        finally:
            recorder.close()
    stats = recorder.stats()
    print(
        f"recorded {stats.messages} messages on {stats.topics} topics in "
        f"{stats.duration_s:.1f} s to {', '.join(recorder.writer.files)}",
        file=sys.stderr,
    )
    return 0


def _record_loop(recorder: Any, stopped: Callable[[], bool], args: argparse.Namespace) -> None:
    from rich.console import Console
    from rich.live import Live

    console = Console(stderr=True)
    live = None if args.no_progress or not console.is_terminal else Live(console=console)
    end = None if args.duration is None else time.monotonic() + args.duration
    next_look = 0.0
    with live if live is not None else _nothing():
        while not stopped() and (end is None or time.monotonic() < end):
            if time.monotonic() >= next_look:
                recorder.discover()
                recorder.writer.flush()
                next_look = time.monotonic() + 1.0
            recorder.context.spin(duration_s=0.1)
            if live is not None:
                live.update(format_progress(recorder.stats()))


def format_progress(stats: Any) -> str:
    """The progress line of ``bag record``, from the recorder's :class:`RecorderStats`."""
    return (
        f"Recording: {stats.messages} messages, {_human_size(stats.size_bytes)}, "
        f"{stats.duration_s:.1f} s, {stats.topics} topics"
    )


@contextmanager
def _nothing() -> Iterator[None]:
    yield


def _stamp(ns: int) -> str:
    moment = datetime.datetime.fromtimestamp(ns / 1e9)
    return f"{moment.strftime('%b %d %Y %H:%M:%S')}.{(ns // 1_000_000) % 1000:03d} ({ns / 1e9:.9f})"


def format_info(summary: Any) -> str:
    """``ros2 bag info``'s block (Jazzy)."""
    lines = [
        "",
        "Files:             " + "\n                   ".join(summary.files),
        f"Bag size:          {_human_size(summary.size_bytes)}",
        f"Storage id:        {summary.storage.value}",
        f"ROS Distro:        {summary.ros_distro or 'unknown'}",
        f"Duration:          {summary.duration_ns / 1e9:.9f}s",
        f"Start:             {_stamp(summary.start_ns)}",
        f"End:               {_stamp(summary.end_ns)}",
        f"Messages:          {summary.message_count}",
    ]
    entries = [
        f"Topic: {t.name} | Type: {t.type} | Count: {t.count} | "
        f"Serialization Format: {t.serialization_format}"
        for t in summary.topics
    ]
    lines.append("Topic information: " + "\n                   ".join(entries))
    return "\n".join(lines)


def _report_damage(damage: Any) -> int:
    for item in damage:
        print(f"robomodel: error: {item}", file=sys.stderr)
    return EXIT_DAMAGED if damage else 0


def run_info(args: argparse.Namespace) -> int:
    from robomodel.bag import open_bag

    bag = open_bag(args.bag)
    summary = bag.summary()
    print(format_info(summary))
    if summary.damage:
        print(
            f"robomodel: warning: {args.bag} is damaged; the counts above cover what could be read",
            file=sys.stderr,
        )
    return _report_damage(summary.damage)


def run_play(args: argparse.Namespace) -> int:
    from robomodel.bag import Player, PlayOptions, open_bag

    if not args.rate > 0:
        raise RobomodelError(f"--rate must be positive, got {args.rate}")
    logging.basicConfig(format="robomodel bag: %(message)s")
    bag = open_bag(args.bag)
    options = PlayOptions(args.rate, args.loop, args.topics, args.clock)
    with (
        stop_on_signals() as stopped,
        context_from_args(args, announce="robomodel bag play") as context,
    ):
        wait_for_peers(context)
        player = Player(context, bag, options)
        if bag.damage:
            print(f"robomodel: warning: {args.bag} is damaged; playing what can be read",
                  file=sys.stderr)  # fmt: skip
        context.spin(duration_s=max(0.0, args.delay))
        player.play(stopped)
    print(f"played {player.published} messages", file=sys.stderr)
    listed = sum(t.count for t in player.summary.topics)
    if not player.published and listed and not stopped():
        why = "" if player.topics else ": robomodel knows none of their types"
        print(f"robomodel: error: {args.bag}: none of its {listed} messages could be played"
              f"{why} (see the warnings above)", file=sys.stderr)  # fmt: skip
        return EXIT_DAMAGED
    return _report_damage(list(dict.fromkeys(bag.damage, None)))
