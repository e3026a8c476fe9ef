"""``robomodel param``: list, get, set, dump and load node parameters (ros2 param), and the
ROS 1 parameter server: on a ROS 1 master (``--bus ros1``, or ROS_MASTER_URI set) every verb
takes rosparam's arguments and prints what rosparam prints (:mod:`robomodel.cli._rosparam`);
on Zenoh, ``param get /name``, ``param set /name VALUE``, ``param delete /name`` and ``param
list /`` reach the parameter server of a ROS 1 launch that ``robomodel launch`` runs."""

from __future__ import annotations

import argparse
from typing import Any

import yaml

from robomodel._escape import escape_name
from robomodel._yaml_bounded import load_yaml
from robomodel.cli._bus import (
    add_bus_arguments,
    bus_from_args,
    context_from_args,
    settled_graph,
    wait_for_peers,
)
from robomodel.cli._verbs import verb_help
from robomodel.errors import RobomodelError
from robomodel.runtime import Context
from robomodel.runtime.param_client import ParameterClient
from robomodel.runtime.params import (
    ParameterError,
    dump_parameters_yaml,
    load_parameters_file,
    parameter_type_name,
    parse_parameter_value,
)

__all__ = ["register"]

_LABELS = {
    "bool": "Boolean value is",
    "integer": "Integer value is",
    "double": "Double value is",
    "string": "String value is",
}


def register(subparsers: Any) -> None:
    parser = subparsers.add_parser("param", help=verb_help("param"))
    verbs = parser.add_subparsers(dest="param_verb", metavar="VERB")
    verbs.required = True
    specs = {
        "list": (["node?"], "parameter names of one node or of every node (ROS 1: [NS])"),
        "get": (["node", "name?"], "print one parameter (NODE NAME; ROS 1: NAME)"),
        "set": (
            ["node", "name?", "value?"],
            "set one parameter (NODE NAME VALUE; ROS 1: NAME VALUE or NAME -t FILE)",
        ),
        "delete": (["node"], "delete a parameter of the ROS 1 parameter server (NAME)"),
        "dump": (["node?", "name?"], "print a node's parameters (NODE; ROS 1: [FILE] [NS])"),
        "load": (["node", "file?"], "set parameters from YAML (NODE FILE; ROS 1: FILE [NS])"),
    }
    for verb, (positionals, help_text) in specs.items():
        p = verbs.add_parser(verb, help=help_text)
        for positional in positionals:
            if positional.endswith("?"):
                p.add_argument(positional[:-1], nargs="?")
            else:
                p.add_argument(positional)
        _add_rosparam_options(verb, p)
        add_bus_arguments(p)
        p.set_defaults(func=globals()[f"run_{verb}"])


def _add_rosparam_options(verb: str, parser: argparse.ArgumentParser) -> None:
    """rosparam's own options (ROS 1 master only)."""
    if verb == "set":
        parser.add_argument(
            "-t", "--textfile", metavar="FILE", help="ROS 1: set the parameter to FILE's text"
        )
        parser.add_argument(
            "-b", "--binfile", metavar="FILE", help="ROS 1: set the parameter to FILE's bytes"
        )
    if verb == "get":
        parser.add_argument(
            "-p", dest="pretty", action="store_true", help="ROS 1: rosparam's pretty print"
        )


def _ros1(verb: str, args: argparse.Namespace) -> int | None:
    """rosparam's command when the bus is a ROS 1 master; None on Zenoh."""
    if bus_from_args(args) != "ros1":
        for option in ("textfile", "binfile", "pretty"):
            if getattr(args, option, None):
                flag = {"textfile": "-t", "binfile": "-b", "pretty": "-p"}[option]
                raise RobomodelError(
                    f"param {verb} {flag} is rosparam's: it needs a ROS 1 master (--bus ros1 "
                    "or ROS_MASTER_URI)"
                )
        return None
    from robomodel.cli._rosparam import run_rosparam

    return _server_call(args, lambda server: run_rosparam(verb, server, args))


def _client(context: Context, node: str) -> ParameterClient:
    return ParameterClient(context, node if node.startswith("/") else f"/{node}")


def run_list(args: argparse.Namespace) -> int:
    code = _ros1("list", args)  # ROS 1 has one parameter tree, no node parameters
    if code is not None:
        return code
    if args.node is not None and args.node.endswith("/"):  # rosparam list [NS/]
        namespace = args.node or "/"

        def show_names(server: Any) -> int:
            for name in server.names():
                if name.startswith(namespace) or namespace == "/":
                    print(escape_name(name))
            return 0

        return _server_call(args, show_names)
    with context_from_args(args) as context:
        if args.node:
            wait_for_peers(context)
            nodes = [args.node]
        else:
            nodes = sorted(settled_graph(context).nodes)
        for node in nodes:
            names = _client(context, node).list_names()
            print(escape_name(f"{node if node.startswith('/') else '/' + node}:"))
            for name in names:
                print(f"  {escape_name(name)}")
    return 0


def _server(context: Context) -> Any:
    from robomodel.launch.param_server import RemoteParamServer

    return RemoteParamServer(context)


def _server_call(args: argparse.Namespace, action: Any) -> int:
    from robomodel.launch.param_server import ParamServerError

    if bus_from_args(args) == "ros1":  # the master's parameter server, as rosparam reads it
        from robomodel.runtime.transport.ros1.names import master_uri
        from robomodel.runtime.transport.ros1.param_client import MasterParams

        uri = master_uri(args.master)
        try:
            return int(action(MasterParams(uri, "/rosparam")))
        except ParamServerError as exc:
            raise RobomodelError(f"{exc} (the ROS 1 master at {uri})") from None
    with context_from_args(args) as context:
        wait_for_peers(context, 3.0)
        try:
            return int(action(_server(context)))
        except ParamServerError as exc:
            raise RobomodelError(
                f"{exc} (the ROS 1 parameter server of `robomodel launch`, domain "
                f"{args.domain_id if args.domain_id is not None else 'default'})"
            ) from None


def _print_value(value: Any) -> int:
    if isinstance(value, dict | list):
        print(yaml.safe_dump(value, default_flow_style=False), end="")
    else:
        print(value)
    return 0


def run_delete(args: argparse.Namespace) -> int:
    code = _ros1("delete", args)
    if code is not None:
        return code
    return _server_call(args, lambda server: server.delete(args.node) or 0)


def run_get(args: argparse.Namespace) -> int:
    code = _ros1("get", args)
    if code is not None:
        return code
    if args.name is None:  # rosparam get /name
        return _server_call(args, lambda server: _print_value(server.get(args.node)))
    with context_from_args(args) as context:
        wait_for_peers(context)
        try:
            value = _client(context, args.node).get([args.name])[args.name]
        except ParameterError:
            print("Parameter not set.")
            return 1
        kind = parameter_type_name(value)
        label = _LABELS.get(kind, f"{kind.replace('_', ' ').capitalize()} value is")
        print(f"{label}: {value}")
    return 0


def run_set(args: argparse.Namespace) -> int:
    code = _ros1("set", args)
    if code is not None:
        return code
    if args.name is None:
        raise RobomodelError("param set: give NODE NAME VALUE (or /NAME VALUE)")
    if args.value is None:  # rosparam set /name VALUE (YAML)
        ros1_value = load_yaml(args.name, what="the parameter value")
        return _server_call(args, lambda server: server.set(args.node, ros1_value) or 0)
    value = parse_parameter_value(args.value)
    with context_from_args(args) as context:
        wait_for_peers(context)
        result = _client(context, args.node).set({args.name: value})[0]
        if result.successful:
            print("Set parameter successful")
            return 0
        print(f"Setting parameter failed: {result.reason}")
        return 1


def run_dump(args: argparse.Namespace) -> int:
    code = _ros1("dump", args)
    if code is not None:
        return code
    if args.node is None or args.name is not None:
        raise RobomodelError("param dump: give one NODE (ros2 param dump NODE)")
    with context_from_args(args) as context:
        wait_for_peers(context)
        client = _client(context, args.node)
        values = client.get(client.list_names())
        print(dump_parameters_yaml(client.node, values), end="")
    return 0


def run_load(args: argparse.Namespace) -> int:
    code = _ros1("load", args)
    if code is not None:
        return code
    if args.file is None:
        raise RobomodelError("param load: give NODE FILE (ros2 param load NODE FILE)")
    node = args.node if args.node.startswith("/") else f"/{args.node}"
    try:
        values = load_parameters_file(args.file, node)
    except OSError as exc:
        raise RobomodelError(f"cannot read '{args.file}': {exc.strerror}") from None
    except yaml.YAMLError as exc:  # pragma: no cover - load_parameters_file wraps these
        raise RobomodelError(str(exc)) from None
    failed = 0
    with context_from_args(args) as context:
        wait_for_peers(context)
        results = _client(context, node).set(values) if values else []
        for name, result in zip(values, results, strict=False):
            if result.successful:
                print(f"Set parameter {name} successful")
            else:
                failed += 1
                print(f"Set parameter {name} failed: {result.reason}")
    return 1 if failed else 0
