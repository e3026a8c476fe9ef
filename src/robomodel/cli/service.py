"""``robomodel service``: list and call services on the bus (``ros2 service list|call``).

robomodel services take and return JSON-like mappings (not typed .srv messages), so a request
is given as YAML, as ``ros2 service call`` takes it, without the type argument::

    robomodel service list
    robomodel service call /gazebo/pause_physics
    robomodel service call /gazebo/step '{steps: 100}'
    robomodel service call /controller_manager/list_controllers
"""

from __future__ import annotations

import argparse
import json
import time
from typing import Any

import yaml

from robomodel.cli._bus import (
    add_bus_arguments,
    context_from_args,
    settled_graph,
    wait_for_peers,
)
from robomodel.cli._verbs import verb_help
from robomodel.errors import RobomodelError

__all__ = ["parse_request", "register"]


def register(subparsers: Any) -> None:
    parser = subparsers.add_parser("service", help=verb_help("service"))
    verbs = parser.add_subparsers(dest="service_verb", metavar="VERB")
    verbs.required = True

    p = verbs.add_parser("list", help="the services offered on the bus")
    add_bus_arguments(p)
    p.set_defaults(func=_run_list)

    p = verbs.add_parser("call", help="call a service with a YAML request and print the reply")
    p.add_argument("service", help="service name, e.g. /gazebo/reset_world")
    p.add_argument("request", nargs="?", default="{}", help="YAML mapping, e.g. '{steps: 10}'")
    p.add_argument(
        "--timeout", type=float, default=3.0, metavar="S", help="give up after S s (default 3)"
    )
    add_bus_arguments(p)
    p.set_defaults(func=_run_call)


def parse_request(text: str) -> dict[str, Any]:
    """The YAML mapping of a request (``''`` and ``{}`` are the empty request)."""
    try:
        value = yaml.safe_load(text) if text.strip() else {}
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        at = f" at line {mark.line + 1}, column {mark.column + 1}" if mark is not None else ""
        raise RobomodelError(
            f"the request is not valid YAML{at}: {getattr(exc, 'problem', exc)}; "
            "give a mapping, e.g. '{steps: 10}'"
        ) from None
    if value is None:
        return {}
    if not isinstance(value, dict):
        raise RobomodelError(
            f"the request must be a YAML mapping such as '{{steps: 10}}', got {text!r}"
        )
    return value


def _run_list(args: argparse.Namespace) -> int:
    with context_from_args(args) as context:
        for name in sorted(settled_graph(context).services):
            print(name)
    return 0


def _run_call(args: argparse.Namespace) -> int:
    name = "/" + args.service.lstrip("/")
    request = parse_request(args.request)
    with context_from_args(args) as context:
        wait_for_peers(context)
        print(f"requester: making request: {json.dumps(request)}\n")
        start = time.monotonic()
        try:
            reply = context.call_service(name, request, timeout_s=args.timeout)
        except RobomodelError as exc:
            offered = sorted(context.graph(timeout_s=0.5).services)
            raise RobomodelError(
                f"{exc}; services on the bus: {', '.join(offered) or '(none found)'}"
            ) from None
        print(f"response ({(time.monotonic() - start) * 1e3:.1f} ms):")
        print(yaml.safe_dump(reply, default_flow_style=False, sort_keys=False).rstrip())
    if "error" in reply and not reply.get("success", reply.get("ok", False)):
        return 2
    return 0
