"""``robomodel service``: list, type and call services on the bus (``ros2 service``).

Services have their ROS 2 types, so a robomodel service answers ``ros2 service call`` and a
real ROS 2 service answers ``robomodel service call``. The request is YAML, as
``ros2 service call`` takes it; the type may be left out when the graph knows it::

    robomodel service list -t
    robomodel service call /gazebo/pause_physics std_srvs/srv/Empty
    robomodel service call /controller_manager/list_controllers
    robomodel service call /talker/get_parameters rcl_interfaces/srv/GetParameters "{names: [gain]}"

On a ROS 1 master the master knows no service types: as ``rosservice`` does, the type is asked
of the service's provider (a TCPROS ``probe=1`` connection), and the request may use ROS 1's
field names (``secs``/``nsecs``, controller_manager_msgs' ``start_controllers``, ...).
"""

from __future__ import annotations

import argparse
import time
from typing import Any

from robomodel._escape import escape_name
from robomodel.cli._bus import (
    add_bus_arguments,
    context_from_args,
    hides,
    settled_graph,
    wait_for_peers,
)
from robomodel.cli._types import add_type_arguments
from robomodel.cli._verbs import verb_help
from robomodel.errors import RobomodelError, close_matches
from robomodel.runtime import Context
from robomodel.runtime.msg import message_from_yaml, message_to_yaml
from robomodel.runtime.msg.schema import Service, get_service_type
from robomodel.runtime.msg.yaml_io import message_from_dict
from robomodel.runtime.transport.base import ServiceCallError

__all__ = ["register", "service_type"]


def register(subparsers: Any) -> None:
    parser = subparsers.add_parser("service", help=verb_help("service"))
    verbs = parser.add_subparsers(dest="service_verb", metavar="VERB")
    verbs.required = True

    p = verbs.add_parser("list", help="the services offered on the bus")
    p.add_argument("-t", "--show-types", action="store_true", help="also print each one's type")
    p.add_argument(
        "--include-hidden-services",
        action="store_true",
        help="also services with a part starting with _ (an action's), as ros2 service list",
    )
    add_bus_arguments(p)
    add_type_arguments(p)
    p.set_defaults(func=_run_list)

    p = verbs.add_parser("type", help="the type of a service")
    p.add_argument("service")
    add_bus_arguments(p)
    add_type_arguments(p)
    p.set_defaults(func=_run_type)

    p = verbs.add_parser("call", help="call a service with a YAML request and print the reply")
    p.add_argument("service", help="service name, e.g. /gazebo/reset_world")
    p.add_argument(
        "type", nargs="?", help="e.g. std_srvs/srv/Empty (default: the type the graph shows)"
    )
    p.add_argument("request", nargs="?", default="{}", help="YAML, e.g. '{names: [gain]}'")
    p.add_argument(
        "--timeout", type=float, default=3.0, metavar="S", help="give up after S s (default 3)"
    )
    add_bus_arguments(p)
    add_type_arguments(p)
    p.set_defaults(func=_run_call)


def _types(context: Context, name: str, types: Any) -> list[str]:
    """The service's types: the graph's, or on ROS 1 the one its provider names."""
    known = sorted(t for t in types if t)  # ROS 1's master knows none: ""
    if known or context.transport.name != "ros1":
        return known
    try:
        return [_probed(context, name, 3.0)]
    except ServiceCallError:
        return []


def _probed(context: Context, name: str, timeout_s: float) -> str:
    """rosservice's type lookup: the provider's ``type`` header, as robomodel names it."""
    from robomodel.runtime.transport.ros1.services import probe_service_type

    ros1_name = probe_service_type(
        context.transport.master_uri,  # type: ignore[attr-defined]
        "/robomodel_service",
        name,
        timeout_s,
    )
    package, _, stem = ros1_name.partition("/")
    return f"{package}/srv/{stem}"


def _run_list(args: argparse.Namespace) -> int:
    with context_from_args(args) as context:
        for name, info in sorted(settled_graph(context).services.items()):
            if hides(context, name, args.include_hidden_services):
                continue
            shown = escape_name(name)  # a peer's name: control characters escaped
            if args.show_types:
                types = ", ".join(escape_name(t) for t in _types(context, name, info.types))
                print(f"{shown} [{types}]")
            else:
                print(shown)
    return 0


def _run_type(args: argparse.Namespace) -> int:
    name = "/" + args.service.lstrip("/")
    with context_from_args(args) as context:
        info = settled_graph(context).services.get(name)
        if info is None:
            raise RobomodelError(_not_offered(context, name))
        for type_name in _types(context, name, info.types):
            print(escape_name(type_name))
    return 0


def _not_offered(context: Context, name: str) -> str:
    """ "service 'x' is not offered on the bus (did you mean ...?)" with the offered names."""
    services = settled_graph(context, 0.5).services
    offered = sorted(name for name, info in services.items() if info.servers)  # not callers
    hint = close_matches(name, offered)
    mean = f" (did you mean {', '.join(repr(h) for h in hint)}?)" if hint else ""
    listing = ", ".join(offered) or "(none found)"
    return f"service '{name}' is not offered on the bus{mean}; services on the bus: {listing}"


def service_type(context: Context, name: str, given: str | None) -> type[Service]:
    """The type to call ``name`` with: ``given``, else the one the graph shows."""
    if given:
        return get_service_type(given)
    info = settled_graph(context).services.get(name)
    if info is not None and not any(info.types) and context.transport.name == "ros1":
        try:
            return get_service_type(_probed(context, name, 3.0))
        except ServiceCallError as exc:
            raise RobomodelError(f"{exc} (give its type to call it anyway)") from None
    if info is None or not info.types:
        raise RobomodelError(f"{_not_offered(context, name)} (give its type to call it anyway)")
    if len(info.types) > 1:
        raise RobomodelError(
            f"service '{name}' is offered with several types ({', '.join(sorted(info.types))}); "
            "give the one to call"
        )
    return get_service_type(next(iter(info.types)))


def _request(context: Context, srv_type: type[Service], text: str) -> Any:
    """The request from its YAML; on ROS 1, ROS 1's field names are taken too."""
    if context.transport.name != "ros1":
        return message_from_yaml(srv_type.Request, text)
    import yaml

    from robomodel._yaml_bounded import load_yaml
    from robomodel.runtime.transport.ros1.ros1_yaml import from_ros1_fields

    try:
        data = load_yaml(text, what="the request") if text.strip() else None
    except yaml.YAMLError as exc:
        reason = " ".join(str(exc).split())
        raise RobomodelError(f"the request is not valid YAML: {reason}") from None
    return message_from_dict(srv_type.Request, from_ros1_fields(srv_type.Request, data))


def _run_call(args: argparse.Namespace) -> int:
    name = "/" + args.service.lstrip("/")
    given, text = args.type, args.request
    if given is not None and ("{" in given or ":" in given):  # the type left out, a request given
        given, text = None, given
    with context_from_args(args) as context:
        wait_for_peers(context)
        srv_type = service_type(context, name, given)
        request = _request(context, srv_type, text)
        print(f"requester: making request: {srv_type.Request.__typename__}")
        print(message_to_yaml(request).rstrip() if request.__fields__ else "{}")
        start = time.monotonic()
        try:
            reply = context.call_service(name, srv_type, request, timeout_s=args.timeout)
        except ServiceCallError as exc:
            info = settled_graph(context, 0.5).services.get(name)
            if info is not None and info.servers:
                raise
            raise RobomodelError(f"{exc}: {_not_offered(context, name)}") from None
        print(f"\nresponse ({(time.monotonic() - start) * 1e3:.1f} ms):")
        print(message_to_yaml(reply).rstrip() if reply.__fields__ else "{}")
    return 0
