"""``robomodel master``: a ROS 1 master and parameter server, as ``roscore``, with roscore's
``/rosout`` node (it republishes ``/rosout`` on ``/rosout_agg``; no rosout.log is written).

ROS 1 nodes, Debian's rostopic/rosparam/rosnode and ``robomodel launch`` of a ROS 1 launch file
find it at ``ROS_MASTER_URI`` (default http://localhost:11311/). It listens on loopback unless
``ROS_IP``/``ROS_HOSTNAME`` name this machine for others. It runs until Ctrl-C or SIGTERM.
"""

from __future__ import annotations

import argparse
import sys
import time
from collections.abc import Callable
from typing import Any

from robomodel.cli._signals import stop_on_signals
from robomodel.cli._verbs import verb_help
from robomodel.errors import RobomodelError

__all__ = ["register"]


def register(subparsers: Any) -> None:
    parser = subparsers.add_parser("master", help=verb_help("master"))
    parser.add_argument(
        "-p", "--port", type=int, default=None,
        help="the port (default: ROS_MASTER_URI's, else 11311), as roscore -p",
    )  # fmt: skip
    parser.add_argument("--duration", type=float, default=None, help="stop after S seconds")
    parser.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    # Ctrl-C and SIGTERM set a flag from here on, start-up included: a KeyboardInterrupt raised
    # while the master and its /rosout node come up escaped the cleanup (exit -2, the master's
    # threads left half-started).
    with stop_on_signals() as stopped:
        return _serve(args, stopped)


def _serve(args: argparse.Namespace, stopped: Callable[[], bool]) -> int:
    from robomodel.runtime.transport.ros1.master import Master, master_answers
    from robomodel.runtime.transport.ros1.names import (
        advertised_host,
        http_uri,
        master_bind_host,
        master_uri,
    )

    uri = master_uri()
    if args.port is not None:
        uri = http_uri(advertised_host(), args.port)
    if master_answers(uri):
        raise RobomodelError(f"a ROS 1 master already answers at {uri}")
    try:
        master = Master(uri, master_bind_host(uri))
    except RobomodelError as exc:
        raise RobomodelError(f"cannot start the master: {exc}") from None
    try:
        return _run_master(args, master, uri, stopped)
    finally:
        master.close()


def _run_master(
    args: argparse.Namespace, master: Any, uri: str, stopped: Callable[[], bool]
) -> int:
    import uuid

    from robomodel.launch.ros1_master import ROSDISTRO, ROSVERSION
    from robomodel.runtime import Context
    from robomodel.runtime.nodes.rosout import RosoutAggregator
    from robomodel.runtime.transport.ros1.names import split_uri

    master.api.params.set("/run_id", str(uuid.uuid1()))
    master.api.params.set("/rosdistro", ROSDISTRO + "\n")
    master.api.params.set("/rosversion", ROSVERSION + "\n")
    with Context("ros1", master=uri) as context:
        rosout = RosoutAggregator(context)
        print(
            f"started ROS 1 master at {uri} (port {split_uri(uri)[1]}); Ctrl-C stops",
            file=sys.stderr,
            flush=True,
        )
        end = None if args.duration is None else time.monotonic() + args.duration
        try:
            while not stopped() and (end is None or time.monotonic() < end):
                context.spin_once(0.1)
        finally:
            rosout.close()
    return 0
