"""``robomodel router``: a Zenoh router for the ROS 2 graph, as ``ros2 run rmw_zenoh_cpp rmw_zenohd``.

On one machine no router command is needed: the first robomodel process becomes the router
when none answers. Across machines, run one router that the others reach::

    robomodel router --listen tcp/0.0.0.0:7447          # on the robot
    ZENOH_CONFIG_OVERRIDE='connect/endpoints=["tcp/robot:7447"]' robomodel view ...   # elsewhere

By default it listens on ``tcp/localhost:7447`` only; ``ZENOH_ROUTER_CONFIG_URI`` and
``ZENOH_CONFIG_OVERRIDE`` apply as they do to ``rmw_zenohd``. It runs until Ctrl-C or SIGTERM.
"""

from __future__ import annotations

import argparse
import signal
import sys
import time
from typing import Any

from robomodel.cli._verbs import verb_help
from robomodel.errors import RobomodelError

__all__ = ["register"]

TRIM_PERIOD_S = 5.0
"""How often the router returns freed memory to the system (see ``release_freed_memory``)."""


def register(subparsers: Any) -> None:
    parser = subparsers.add_parser("router", help=verb_help("router"))
    parser.add_argument(
        "--listen",
        action="append",
        default=[],
        metavar="ENDPOINT",
        help="listen here instead of tcp/localhost:7447 (repeatable), e.g. tcp/0.0.0.0:7447",
    )
    parser.add_argument("--duration", type=float, default=None, help="stop after S seconds")
    parser.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from robomodel.runtime.transport._zenoh_common import import_zenoh, release_freed_memory
    from robomodel.runtime.transport._zenoh_session import router_config

    zenoh = import_zenoh()
    conf = router_config(args.listen)
    try:
        session = zenoh.open(conf)
    except Exception as exc:
        raise RobomodelError(
            f"cannot start the router: {exc} (is another router, or a robomodel process acting "
            "as one, already listening there?)"
        ) from None
    stopped: list[bool] = []  # a flag, not an Event: a second SIGTERM must not wait on a lock
    previous = signal.signal(signal.SIGTERM, lambda *_: stopped.append(True))
    print(
        f"Started Zenoh router with id {session.zid()}; listening on "
        f"{', '.join(args.listen) or 'tcp/localhost:7447'}; Ctrl-C stops",
        file=sys.stderr,
        flush=True,
    )
    end = None if args.duration is None else time.monotonic() + args.duration
    next_trim = time.monotonic() + TRIM_PERIOD_S
    try:
        while not stopped and (end is None or time.monotonic() < end):
            time.sleep(0.1)
            if time.monotonic() >= next_trim:  # what peers' tokens took goes back when they go
                release_freed_memory()
                next_trim = time.monotonic() + TRIM_PERIOD_S
    except KeyboardInterrupt:
        pass
    finally:
        signal.signal(signal.SIGTERM, previous)
        session.close()
    return 0
