"""Run by the zenoh-ros2-sdk venv's Python (not robomodel's): an independent rmw_zenoh peer.

    python sdk_agent.py --messages DIR --domain N COMMAND ...

Commands (each prints JSON lines on stdout, then exits):
    subscribe TOPIC TYPE SECONDS COUNT   messages received (as dicts), up to COUNT
    publish TOPIC TYPE JSON RATE SECONDS publish the message JSON at RATE Hz; with --describe,
                                         its node answers ~/get_type_description too
    call SERVICE TYPE JSON               the response of one call (as a dict), or {"error": ...}
    topics                               [[name, [types]], ...] from the SDK's discovery
    services                             likewise for services
    hash TYPE                            the SDK's own RIHS01 hash of a msg or srv type

Message definitions come from DIR (written by ``msgtext.write_definitions``): the SDK would
otherwise clone them from GitHub.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import threading
import time
from pathlib import Path
from typing import Any


def _plain(value: Any) -> Any:
    """A rosbags message (or numpy array) as JSON-able data."""
    if hasattr(value, "tolist"):
        return value.tolist()
    if hasattr(value, "__dataclass_fields__"):
        return {
            k: _plain(getattr(value, k)) for k in value.__dataclass_fields__ if k != "__msgtype__"
        }
    if isinstance(value, list | tuple):
        return [_plain(v) for v in value]
    return value


def _build(store: Any, typename: str, data: dict[str, Any]) -> Any:
    """A rosbags message of ``typename`` from a (partial) dict: defaults for what is missing."""
    import numpy as np

    cls = store.types[typename]
    _, fields = store.fielddefs[typename]
    values = {}
    for name, (kind, rest) in fields:
        given = data.get(name)
        values[name] = _field(store, np, kind, rest, given)
    return cls(**values)


_DTYPES = {"float64": "f8", "float32": "f4", "int64": "i8", "uint64": "u8", "int32": "i4",
           "uint32": "u4", "int16": "i2", "uint16": "u2", "int8": "i1", "uint8": "u1",
           "byte": "u1", "char": "u1", "bool": "bool"}  # fmt: skip


def _field(store: Any, np: Any, kind: int, rest: Any, given: Any) -> Any:
    if kind == 1:  # BASE
        name = rest[0]
        if given is not None:
            return given
        return "" if name == "string" else (False if name == "bool" else 0)
    if kind == 2:  # NAME
        return _build(store, rest, given or {})
    item_kind, item_rest = rest[0]
    items = list(given or [])
    if kind == 3 and not items:  # ARRAY: its fixed size
        items = [None] * rest[1]
    if item_kind == 1 and item_rest[0] != "string":
        return np.array([v or 0 for v in items], dtype=_DTYPES[item_rest[0]])
    return [_field(store, np, item_kind, item_rest, v) for v in items]


def _emit(value: Any) -> None:
    print(json.dumps(value), flush=True)


def _subscribe(args: argparse.Namespace, domain: int) -> None:
    from zenoh_ros2_sdk import ROS2Subscriber

    got: list[Any] = []
    done = threading.Event()
    lock = threading.Lock()

    def on_message(msg: Any) -> None:
        # Messages that arrive after the count (before close() returns, which takes long on
        # a loaded machine) are not printed: 8 came out where 3 were asked for.
        with lock:
            if len(got) >= args.count:
                return
            _emit(_plain(msg))
            got.append(1)
            if len(got) >= args.count:
                done.set()

    sub = ROS2Subscriber(
        topic=args.topic, msg_type=args.type, callback=on_message, domain_id=domain
    )
    done.wait(args.seconds)
    sub.close()


# type_description_interfaces/msg/FieldType.msg (rcl_interfaces, jazzy): the ids of the base
# types (as rosbags names them), plus 48 for T[N], 96 for T[<=N], 144 for T[]; 1 is a nested type.
_FIELD_TYPE_IDS = {"int8": 2, "uint8": 3, "int16": 4, "uint16": 5, "int32": 6, "uint32": 7,
                   "int64": 8, "uint64": 9, "float32": 10, "float64": 11, "bool": 15,
                   "octet": 16, "string": 17}  # fmt: skip


def _described_field(name: str, desc: Any, used: list[str]) -> dict[str, Any]:
    """One Field of a TypeDescription, as rosidl_generator_type_description's ``field_type``
    writes it (ros2/rosidl ``rosidl_generator_type_description/__init__.py``)."""
    kind, rest = desc
    offset, capacity = 0, 0
    if kind in (3, 4):  # ARRAY, SEQUENCE: their item, with the offset of the container
        (item_kind, item), size = rest
        offset = 48 if kind == 3 else (96 if size else 144)
        kind, rest, capacity = item_kind, item, size
    nested, string_capacity = "", 0
    if kind == 2:  # NAME
        type_id, nested = 1, str(rest)
        used.append(nested)
    elif rest[0] == "string" and rest[1]:
        type_id, string_capacity = 21, int(rest[1])
    else:
        type_id = _FIELD_TYPE_IDS[rest[0]]
    return {"name": name, "default_value": "",
            "type": {"type_id": type_id + offset, "capacity": capacity,
                     "string_capacity": string_capacity, "nested_type_name": nested}}  # fmt: skip


def _type_description(store: Any, typename: str) -> dict[str, Any]:
    """The TypeDescription of ``typename`` from the SDK's store: the type, then the types it
    references (recursively), sorted by name (REP-2011, rosidl_generator_type_description)."""
    individuals: dict[str, Any] = {}
    pending = [typename]
    while pending:
        name = pending.pop()
        if name in individuals:
            continue
        used: list[str] = []
        fields = store.fielddefs[name][1] or [
            ("structure_needs_at_least_one_member", (1, ("uint8", 0)))
        ]
        individuals[name] = {"type_name": name,
                             "fields": [_described_field(n, d, used) for n, d in fields]}  # fmt: skip
        pending.extend(used)
    top = individuals.pop(typename)
    return {"type_description": top,
            "referenced_type_descriptions": [individuals[n] for n in sorted(individuals)]}  # fmt: skip


def _serve_descriptions(args: argparse.Namespace, domain: int, pub: Any) -> Any:
    """``/sdk_talker/get_type_description`` for the publisher's type, answered as rcl's
    ``rcl_node_type_description_service_handle_request`` (ros2/rcl ``node.c``): by hash, with
    the sources (the ``.msg`` files) only when asked."""
    from zenoh_ros2_sdk import ROS2ServiceServer

    srv = "type_description_interfaces/srv/GetTypeDescription"
    request_text, _, response_text = (
        (Path(args.messages) / "type_description_interfaces/srv/GetTypeDescription.srv")
        .read_text()
        .partition("---\n")
    )
    _register_messages(pub.session_mgr, Path(args.messages))
    store = pub.session_mgr.store
    holder: dict[str, Any] = {}

    def answer(request: Any) -> Any:
        if request.type_hash != pub.type_hash:
            data: dict[str, Any] = {"failure_reason": "Type not currently in use by this node"}
        else:
            description = _type_description(store, args.type)
            names = [description["type_description"]["type_name"]]
            names += [d["type_name"] for d in description["referenced_type_descriptions"]]
            sources = []
            for name in names if request.include_type_sources else []:
                package, _, short = name.split("/")
                text = (Path(args.messages) / package / "msg" / f"{short}.msg").read_text()
                sources.append({"type_name": name, "encoding": "msg", "raw_file_contents": text})
            data = {"successful": True, "type_description": description, "type_sources": sources}
        return _build(store, holder["server"].response_store_type, data)

    holder["server"] = ROS2ServiceServer(
        "/sdk_talker/get_type_description", srv, callback=answer,
        request_definition=request_text, response_definition=response_text,
        node_name="sdk_talker", domain_id=domain,
    )  # fmt: skip
    return holder["server"]


def _publish(args: argparse.Namespace, domain: int) -> None:
    from zenoh_ros2_sdk import ROS2Publisher

    pub = ROS2Publisher(
        topic=args.topic, msg_type=args.type, domain_id=domain, node_name="sdk_talker"
    )
    server = _serve_descriptions(args, domain, pub) if args.describe else None
    store = pub.session_mgr.store
    message = _build(store, args.type, json.loads(args.json))
    fields = {k: getattr(message, k) for k in message.__dataclass_fields__ if k != "__msgtype__"}
    end = time.monotonic() + args.seconds
    sent = 0
    while time.monotonic() < end:
        pub.publish(**fields)
        sent += 1
        time.sleep(1.0 / args.rate)
    pub.close()
    if server is not None:
        server.close()
    _emit({"sent": sent})


def _register_messages(session: Any, directory: Path) -> None:
    """Every message of ``directory`` in the session's store: a response's nested types
    (TypeDescription's) are not always registered with it."""
    for path in sorted(directory.glob("*/msg/*.msg")):
        session.register_message_type(path.read_text(), f"{path.parts[-3]}/msg/{path.stem}")


def _call(args: argparse.Namespace, domain: int) -> None:
    from zenoh_ros2_sdk import ROS2ServiceClient

    package, _, name = args.type.split("/")
    text = (Path(args.messages) / package / "srv" / f"{name}.srv").read_text()
    request, _, response = text.partition("---\n")
    # The SDK cannot hash a service whose request is empty; the caller passes the hash then.
    client = ROS2ServiceClient(
        args.service,
        args.type,
        request_definition=request,
        response_definition=response,
        domain_id=domain,
        timeout=10.0,
        type_hash=args.type_hash or None,
    )
    _register_messages(client.session_mgr, Path(args.messages))
    store = client.session_mgr.store
    request = _build(store, client.request_store_type, json.loads(args.json))
    fields = {k: getattr(request, k) for k in request.__dataclass_fields__ if k != "__msgtype__"}
    response = client.call(**fields)
    _emit(
        {"type_hash": client.type_hash, "response": _plain(response)}
        if response is not None
        else {"error": "no response"}
    )
    client.close()


def _hash(args: argparse.Namespace, directory: Path) -> None:
    from zenoh_ros2_sdk.message_registry import get_registry
    from zenoh_ros2_sdk.utils import (
        compute_service_type_hash,
        get_type_hash,
        load_dependencies_recursive,
    )

    registry = get_registry()
    package, kind, name = args.type.split("/")
    if kind == "srv":
        request, _, response = (
            (directory / package / "srv" / f"{name}.srv").read_text().partition("---\n")
        )
        deps = {
            **load_dependencies_recursive(f"{package}/srv/{name}_Request", request, registry),
            **load_dependencies_recursive(f"{package}/srv/{name}_Response", response, registry),
        }
        _emit(compute_service_type_hash(args.type, request, response, dependencies=deps))
    else:
        text = (directory / package / "msg" / f"{name}.msg").read_text()
        deps = load_dependencies_recursive(args.type, text, registry)
        _emit(get_type_hash(args.type, msg_definition=text, dependencies=deps))


def main() -> int:
    parser = argparse.ArgumentParser()
    parser.add_argument("--messages", required=True)
    parser.add_argument("--domain", type=int, default=0)
    verbs = parser.add_subparsers(dest="verb", required=True)
    p = verbs.add_parser("subscribe")
    p.add_argument("topic"); p.add_argument("type"); p.add_argument("seconds", type=float); p.add_argument("count", type=int)  # fmt: skip  # noqa: E702
    p = verbs.add_parser("publish")
    p.add_argument("topic"); p.add_argument("type"); p.add_argument("json"); p.add_argument("rate", type=float); p.add_argument("seconds", type=float)  # fmt: skip  # noqa: E702
    p.add_argument("--describe", action="store_true")
    p = verbs.add_parser("call")
    p.add_argument("service"); p.add_argument("type"); p.add_argument("json")  # fmt: skip  # noqa: E702
    p.add_argument("--type-hash", default="")
    verbs.add_parser("topics")
    verbs.add_parser("services")
    p = verbs.add_parser("hash")
    p.add_argument("type")
    args = parser.parse_args()

    from zenoh_ros2_sdk.message_registry import get_registry

    registry = get_registry(args.messages)  # before anything creates the registry without it
    if args.verb in ("call", "publish"):  # nested types, which the SDK loads only to hash
        for path in sorted(Path(args.messages).glob("*/msg/*.msg")):
            registry.load_message_type(f"{path.parts[-3]}/msg/{path.stem}")
    if args.verb == "subscribe":
        _subscribe(args, args.domain)
    elif args.verb == "publish":
        _publish(args, args.domain)
    elif args.verb == "call":
        _call(args, args.domain)
    elif args.verb in ("topics", "services"):
        from zenoh_ros2_sdk import (
            ZenohSession,
            get_service_names_and_types,
            get_topic_names_and_types,
        )

        ZenohSession.get_instance()  # connect first: discovery reads what the router knows
        # the test's timeout scale (tests/timing.py; this runs in the SDK's own venv)
        scale = float(os.environ.get("ROBOMODEL_TEST_TIMEOUT_SCALE") or 1.0)
        time.sleep(1.0 * scale)
        lister = get_topic_names_and_types if args.verb == "topics" else get_service_names_and_types
        found = lister(domain_id=args.domain, timeout=2.0 * scale)
        _emit([[name, list(types)] for name, types in found])
    else:
        _hash(args, Path(args.messages))
    return 0


if __name__ == "__main__":
    sys.exit(main())
