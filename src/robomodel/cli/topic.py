"""``robomodel topic``: list, echo, pub, hz and info, with ``ros2 topic``'s output."""

from __future__ import annotations

import argparse
import itertools
import math
import statistics
import sys
import time
from typing import Any

from robomodel._escape import escape_name, escape_names
from robomodel.cli._bus import (
    add_bus_arguments,
    context_from_args,
    hides,
    listing_exit_code,
    settled_graph,
    wait_for_peers,
)
from robomodel.cli._types import add_type_arguments
from robomodel.cli._verbs import verb_help
from robomodel.errors import RobomodelError
from robomodel.runtime import Context
from robomodel.runtime.msg import (
    Message,
    MessageTypeError,
    get_message_type,
    message_from_yaml,
    message_to_yaml,
)
from robomodel.runtime.msg.schema import canonical_type_name
from robomodel.runtime.qos import Durability, History, QoSProfile, Reliability

__all__ = ["register"]


def register(subparsers: Any) -> None:
    parser = subparsers.add_parser("topic", help=verb_help("topic"))
    verbs = parser.add_subparsers(dest="topic_verb", metavar="VERB")
    verbs.required = True
    _add_list_verb(verbs)
    _add_echo_verb(verbs)
    _add_pub_verb(verbs)
    _add_hz_verb(verbs)
    _add_info_verb(verbs)


def _add_list_verb(verbs: Any) -> None:
    p = verbs.add_parser("list", help="the topics that exist")
    p.add_argument("-t", "--show-types", action="store_true", help="also print each topic's type")
    p.add_argument(
        "--include-hidden-topics",
        action="store_true",
        help="also topics with a part starting with _ (an action's feedback), as ros2 topic list",
    )
    add_bus_arguments(p)
    add_type_arguments(p)
    p.set_defaults(func=run_list)


def _add_echo_verb(verbs: Any) -> None:
    p = verbs.add_parser("echo", help="print messages as YAML documents")
    p.add_argument("topic")
    p.add_argument("type", nargs="?", help="message type (default: the publisher's type)")
    p.add_argument("--once", action="store_true", help="print one message and exit")
    p.add_argument("--count", type=int, default=None, metavar="N", help="exit after N messages")
    p.add_argument(
        "--timeout",
        type=float,
        default=None,
        metavar="S",
        help="give up after S seconds (the wait for a publisher to learn the type from included)",
    )
    q = p.add_argument_group("quality of service (as ros2 topic echo's)")
    q.add_argument(
        "--qos-depth", type=int, default=10, metavar="N",
        help="messages kept waiting to be printed (default 10): a printer that falls "
        "further behind drops the oldest",
    )  # fmt: skip
    q.add_argument(
        "--qos-history", choices=[h.value for h in History], default=History.KEEP_LAST.value,
        help="keep_all keeps every message until it is printed (default keep_last)",
    )  # fmt: skip
    q.add_argument(
        "--qos-reliability", choices=[r.value for r in Reliability],
        default=Reliability.RELIABLE.value, help="default reliable",
    )  # fmt: skip
    q.add_argument(
        "--qos-durability", choices=[d.value for d in Durability],
        default=Durability.TRANSIENT_LOCAL.value,
        help="default transient_local: a latched topic's last messages come too",
    )  # fmt: skip
    q.add_argument(
        "--no-lost-messages", action="store_true",
        help="do not report messages lost between the publishers and this echo",
    )  # fmt: skip
    add_bus_arguments(p)
    add_type_arguments(p)
    p.set_defaults(func=run_echo)


def _add_pub_verb(verbs: Any) -> None:
    p = verbs.add_parser("pub", help="publish a message given as YAML")
    p.add_argument("topic")
    p.add_argument("type", help="e.g. std_msgs/msg/Float64 or std_msgs/Float64")
    p.add_argument("values", nargs="?", default="{}", help="YAML, e.g. 'data: 1.5'")
    p.add_argument("-r", "--rate", type=float, default=1.0, help="publishing rate [Hz] (default 1)")
    p.add_argument("-1", "--once", action="store_true", help="publish one message and exit")
    p.add_argument("-t", "--times", type=int, default=None, help="publish N messages and exit")
    p.add_argument(
        "-w",
        "--wait-matching-subscriptions",
        type=int,
        default=None,
        metavar="N",
        help="wait for N matching subscriptions before publishing (default 1 with --once/--times)",
    )
    add_bus_arguments(p)
    add_type_arguments(p)
    p.set_defaults(func=run_pub)


def _add_hz_verb(verbs: Any) -> None:
    p = verbs.add_parser("hz", help="print the average publishing rate")
    p.add_argument("topic")
    p.add_argument("-w", "--window", type=int, default=10000, help="samples in the window")
    p.add_argument("--duration", type=float, default=None, metavar="S", help="stop after S seconds")
    add_bus_arguments(p)
    add_type_arguments(p)
    p.set_defaults(func=run_hz)


def _add_info_verb(verbs: Any) -> None:
    p = verbs.add_parser("info", help="type and publisher/subscription counts of a topic")
    p.add_argument("topic")
    p.add_argument("-v", "--verbose", action="store_true", help="list every endpoint")
    add_bus_arguments(p)
    add_type_arguments(p)
    p.set_defaults(func=run_info)


def _topic_type(context: Context, topic: str, given: str | None, wait_s: float) -> type[Message]:
    if given:
        return get_message_type(given)
    deadline = time.monotonic() + wait_s
    while True:
        info = context.graph(timeout_s=0.3).topics.get(topic)
        if info and info.types:
            if len(info.types) > 1:
                raise RobomodelError(
                    f"topic {escape_name(topic)} has several types "
                    f"({escape_names(sorted(info.types))}); give one"
                )
            found = _type_named(context, topic, next(iter(info.types)), info.publishers)
            _warn_other_hashes(topic, found, info.publishers)
            return found
        if time.monotonic() >= deadline:
            raise RobomodelError(
                f"could not determine the type of {escape_name(topic)}: no publisher found; "
                "pass the type, "
                "e.g. robomodel topic echo /x std_msgs/msg/Float64"
            )
        time.sleep(0.1)


def _type_named(context: Context, topic: str, name: str, publishers: Any) -> type[Message]:
    """The class of ``name``; a type robomodel does not know is learned from its publishers:
    the definition a ROS 1 publisher sends (as rostopic echo decodes any type), or the type
    description a ROS 2 publisher's node gives (``~/get_type_description``)."""
    try:
        return get_message_type(name)
    except MessageTypeError as exc:
        from robomodel.runtime.type_learning import learn_topic_type

        if not learn_topic_type(context, topic, list(publishers)):
            raise MessageTypeError(
                f"{exc}; and no publisher of {escape_name(topic)} described it"
            ) from None
    return get_message_type(name)


def _warn_other_hashes(topic: str, kind: type[Message], publishers: Any) -> None:
    """One line per RIHS01 hash a publisher has that robomodel's class of the type has not:
    a different definition of the same name (another distribution, another package version),
    which rmw_zenoh keeps apart."""
    from robomodel.runtime.msg.typehash import type_hash

    ours = type_hash(kind)
    for theirs in sorted({e.type_hash for e in publishers if e.type_hash.startswith("RIHS01_")}):
        if theirs != ours:
            print(
                f"warning: {topic}: a publisher's {kind.__typename__} has hash {theirs}, "
                f"robomodel's {ours} (another definition; see --distro and --package-path)",
                file=sys.stderr,
            )


def run_list(args: argparse.Namespace) -> int:
    with context_from_args(args) as context:
        graph = settled_graph(context)
        for name in sorted(graph.topics):
            if hides(context, name, args.include_hidden_topics):
                continue
            info = graph.topics[name]
            suffix = f" [{escape_names(sorted(info.types))}]" if args.show_types else ""
            print(f"{escape_name(name)}{suffix}")
    return listing_exit_code(graph)


def run_echo(args: argparse.Namespace) -> int:
    limit = 1 if args.once else args.count
    # until Ctrl-C: say which graph it listens to; a counted echo prints only messages
    announce = "robomodel topic echo" if limit is None else None
    # --timeout bounds the whole wait: for the topic's type too, when it is not given
    deadline = math.inf if args.timeout is None else time.monotonic() + args.timeout

    def left_s() -> float:
        return max(0.0, deadline - time.monotonic())

    with context_from_args(args, announce=announce) as context:
        wait_for_peers(context, min(1.0, left_s()))
        node = context.create_node("robomodel_topic_echo")
        topic = node.resolve_topic_name(args.topic)
        msg_type = _topic_type(context, topic, args.type, min(5.0, left_s()))
        printed = [0]
        lost = [0]

        def show(msg: Message) -> None:
            if limit is not None and printed[0] >= limit:
                return
            now_lost = 0 if args.no_lost_messages else subscription.get_messages_lost()
            if now_lost > lost[0]:  # ros2 topic echo's report of a MESSAGE_LOST event
                sys.stdout.write(
                    f"A message was lost!!!\n\ttotal count change:{now_lost - lost[0]}\n"
                    f"\ttotal count: {now_lost}---\n"
                )
                lost[0] = now_lost
            sys.stdout.write(message_to_yaml(msg) + "---\n")
            sys.stdout.flush()
            printed[0] += 1

        subscription = node.create_subscription(msg_type, args.topic, show, _echo_qos(args))
        try:
            context.spin(
                duration_s=None if args.timeout is None else left_s(),
                until=lambda: limit is not None and printed[0] >= limit,
            )
        except KeyboardInterrupt:
            return 0
    return 0 if limit is None or printed[0] >= limit else 1


def _echo_qos(args: argparse.Namespace) -> QoSProfile:
    """The echo's subscription QoS from its ``--qos-*`` options."""
    if args.qos_depth < 1:
        raise RobomodelError(f"--qos-depth must be 1 or more, got {args.qos_depth}")
    return QoSProfile(
        depth=args.qos_depth,
        durability=Durability(args.qos_durability),
        reliability=Reliability(args.qos_reliability),
        history=History(args.qos_history),
    )


def _wait_subscribers(context: Context, topic: str, count: int, timeout_s: float = 5.0) -> None:
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        info = context.graph(timeout_s=0.2).topics.get(topic)
        if info and sum(e.node != "/robomodel_topic_pub" for e in info.subscribers) >= count:
            time.sleep(0.05)
            return
        time.sleep(0.05)


def run_pub(args: argparse.Namespace) -> int:
    msg_type = get_message_type(args.type)
    message = message_from_yaml(msg_type, args.values)
    times = 1 if args.once else args.times
    if not args.rate > 0 or not math.isfinite(args.rate):
        raise RobomodelError(f"--rate must be a positive number of Hz, got {args.rate}")
    with context_from_args(args, announce=None if times else "robomodel topic pub") as context:
        wait_for_peers(context)
        node = context.create_node("robomodel_topic_pub")
        publisher = node.create_publisher(msg_type, args.topic)
        wait = args.wait_matching_subscriptions
        if wait is None:
            wait = 1 if times is not None else 0
        if wait:
            _wait_subscribers(context, publisher.topic, wait)
        print("publisher: beginning loop")
        type_label = canonical_type_name(args.type).replace("/", ".")
        count = 0
        try:
            while times is None or count < times:
                count += 1
                publisher.publish(message)
                print(f"publishing #{count}: {type_label}({_fields(message)})\n")
                sys.stdout.flush()
                if times is not None and count >= times:
                    break
                context.spin(duration_s=1.0 / args.rate)
            context.spin(duration_s=0.2)  # let the last message leave before closing
        except KeyboardInterrupt:
            return 0
    return 0


def _fields(msg: Message) -> str:
    return ", ".join(f"{name}={_field_repr(getattr(msg, name))}" for name in msg.field_names())


def _field_repr(value: object) -> str:
    # rosidl's __repr__ strips array('B', ...) off a uint8[]: ros2 topic pub shows [1, 2, 3]
    return repr(list(value)) if isinstance(value, bytes) else repr(value)


def run_hz(args: argparse.Namespace) -> int:
    with context_from_args(args, announce="robomodel topic hz") as context:
        wait_for_peers(context)
        node = context.create_node("robomodel_topic_hz")
        msg_type = _topic_type(context, node.resolve_topic_name(args.topic), None, 10.0)
        stamps: list[float] = []

        def on_msg(_: Message) -> None:
            stamps.append(time.monotonic())
            del stamps[: -args.window - 1]

        node.create_subscription(msg_type, args.topic, on_msg, 100)
        start = time.monotonic()
        next_report = start + 1.0
        try:
            while args.duration is None or time.monotonic() - start < args.duration:
                context.spin(duration_s=max(0.0, next_report - time.monotonic()))
                next_report += 1.0
                print(_hz_report(stamps))
                sys.stdout.flush()
        except KeyboardInterrupt:
            return 0
    return 0


def _hz_report(stamps: list[float]) -> str:
    """``ros2 topic hz``'s block: average rate, min/max/std dev of the periods, window size."""
    if len(stamps) < 2:
        return "no new messages"
    periods = [b - a for a, b in itertools.pairwise(stamps)]
    mean = statistics.fmean(periods)
    std = statistics.pstdev(periods)
    return (
        f"average rate: {1.0 / mean:.3f}\n\tmin: {min(periods):.3f}s max: {max(periods):.3f}s "
        f"std dev: {std:.5f}s window: {len(stamps)}"
    )


def run_info(args: argparse.Namespace) -> int:
    with context_from_args(args) as context:
        graph = settled_graph(context)
        info = graph.topics.get(args.topic)
        if info is None:
            known = escape_names(sorted(graph.topics)) or "(none)"
            raise RobomodelError(f"Unknown topic '{escape_name(args.topic)}'; topics: {known}")
        print(f"Type: {escape_names(sorted(info.types))}")
        print(f"Publisher count: {len(info.publishers)}")
        if args.verbose:
            for endpoint in info.publishers:
                print(
                    f"  Node name: {escape_name(endpoint.node)}  QoS depth: {endpoint.qos.depth}  Durability: {endpoint.qos.durability.value}"
                )
        print(f"Subscription count: {len(info.subscribers)}")
        if args.verbose:
            for endpoint in info.subscribers:
                print(
                    f"  Node name: {escape_name(endpoint.node)}  QoS depth: {endpoint.qos.depth}  Durability: {endpoint.qos.durability.value}"
                )
    return listing_exit_code(graph)
