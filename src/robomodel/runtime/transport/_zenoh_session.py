"""Opening a Zenoh session as rmw_zenoh does, and the router robomodel starts when none runs.

The session's configuration is rmw_zenoh's (``DEFAULT_RMW_ZENOH_SESSION_CONFIG.json5``): peer
mode, connect to the router at ``tcp/localhost:7447``, listen on a free loopback port, no
multicast scouting, gossip on, timestamps on. ``ZENOH_SESSION_CONFIG_URI`` replaces it with a
file and ``ZENOH_CONFIG_OVERRIDE`` (``key=json5 value;...``) changes keys of it, as in
rmw_zenoh's ``zenoh_config.cpp``; robomodel's own ``--connect`` / ``--listen`` endpoints (and
``ROBOMODEL_CONNECT`` / ``ROBOMODEL_LISTEN``) are added last.

As rmw_zenoh's context, the session then looks for a router as ``ZENOH_ROUTER_CHECK_ATTEMPTS``
says (see ``_zenoh_router``). When none answers and the configuration names a router on this
machine (a loopback endpoint: by default ``tcp/localhost:7447``), a detached ``robomodel
router`` is started there, which outlives this process and ends when no session has used it for
a minute, so one machine needs no extra command; ``rmw_zenohd`` started first is used instead.
"""

from __future__ import annotations

import json
import os
import time
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from robomodel.errors import RobomodelError
from robomodel.runtime.transport._zenoh_common import import_zenoh, log
from robomodel.runtime.transport._zenoh_router import (
    check_attempts,
    read_record,
    start_router,
    wait_for_router,
)

__all__ = [
    "DEFAULT_ROUTER",
    "ZenohConfigError",
    "apply_override",
    "open_session",
    "parse_override",
    "router_config",
]

DEFAULT_ROUTER = "tcp/localhost:7447"
_LOOPBACK_HOSTS = ("tcp/localhost:", "tcp/127.0.0.1:", "tcp/[::1]:")

# DEFAULT_RMW_ZENOH_SESSION_CONFIG.json5, the keys that differ from Zenoh's defaults. The
# scouting delay is Zenoh's 1.0 default's short one: with multicast off there is nothing to
# wait for, and Zenoh's 500 ms would be paid by every robomodel command.
_SESSION = {
    "mode": "peer",
    "connect/endpoints": [DEFAULT_ROUTER],
    "listen/endpoints": ["tcp/localhost:0"],
    "scouting/delay": 1,
    # Back to a router that restarted (or to the next robomodel process that became it) within
    # a second, rather than Zenoh's 4 s at most.
    "connect/retry": {"period_init_ms": 250, "period_max_ms": 1000, "period_increase_factor": 2},
    "scouting/multicast/enabled": False,
    "scouting/gossip/enabled": True,
    "scouting/gossip/multihop": False,
    "timestamping/enabled": {"router": True, "peer": True, "client": False},
    "queries_default_timeout": 600000,
}
_ROUTER = {
    **_SESSION,
    "mode": "router",
    "connect/endpoints": [],
    "listen/endpoints": [DEFAULT_ROUTER],
}


ROUTER_START_WAIT_S = 10.0


class ZenohConfigError(RobomodelError):
    """A Zenoh configuration file or override that cannot be used."""


def parse_override(text: str) -> list[tuple[str, str]]:
    """``ZENOH_CONFIG_OVERRIDE``: ``key=value`` pairs separated by ``;`` (values are JSON5)."""
    pairs = []
    for part in text.split(";"):
        part = part.strip()
        if not part:
            continue
        key, sep, value = part.partition("=")
        if not sep or not key.strip() or not value.strip():
            raise ZenohConfigError(
                f"ZENOH_CONFIG_OVERRIDE: '{part}' is not key=value, e.g. "
                '\'mode="client";connect/endpoints=["tcp/192.168.1.5:7447"]\''
            )
        pairs.append((key.strip(), value.strip()))
    return pairs


def apply_override(conf: Any, text: str) -> None:
    for key, value in parse_override(text):
        try:
            conf.insert_json5(key, value)
        except Exception as exc:
            raise ZenohConfigError(
                f"ZENOH_CONFIG_OVERRIDE: cannot set {key}={value}: {exc}"
            ) from None


def _config(zenoh: Any, defaults: dict[str, Any], uri_variable: str) -> Any:
    uri = os.environ.get(uri_variable, "").strip()
    if uri:
        try:
            conf = zenoh.Config.from_file(uri)
        except Exception as exc:
            raise ZenohConfigError(
                f"{uri_variable}={uri}: not a usable Zenoh configuration: {exc}"
            ) from None
    else:
        conf = zenoh.Config()
        for key, value in defaults.items():
            conf.insert_json5(key, json.dumps(value))
    apply_override(conf, os.environ.get("ZENOH_CONFIG_OVERRIDE", ""))
    return conf


def _endpoints(conf: Any, key: str) -> list[str]:
    try:
        value = json.loads(conf.get_json(key))
    except Exception:
        return []
    return [str(v) for v in value] if isinstance(value, list) else []


def _add_endpoints(conf: Any, key: str, extra: Sequence[str]) -> None:
    if extra:
        conf.insert_json5(key, json.dumps([*_endpoints(conf, key), *extra]))


def router_config(listen: Sequence[str] = ()) -> Any:
    """The configuration of ``robomodel router`` (``ZENOH_ROUTER_CONFIG_URI`` honoured)."""
    zenoh = import_zenoh()
    conf = _config(zenoh, _ROUTER, "ZENOH_ROUTER_CONFIG_URI")
    if listen:
        conf.insert_json5("listen/endpoints", json.dumps(list(listen)))
    conf.insert_json5("listen/exit_on_failure", "true")  # as rmw_zenohd: a taken port is an error
    return conf


def _env_list(name: str) -> list[str]:
    return [p.strip() for p in os.environ.get(name, "").split(",") if p.strip()]


@dataclass
class OpenedSession:
    session: Any
    is_router: bool
    routers: tuple[str, ...] = ()  # the router endpoints it connects to
    started_router: bool = False  # a detached router was started for it


def open_session(connect: Sequence[str] = (), listen: Sequence[str] = ()) -> OpenedSession:
    """A session joined to the ROS 2 graph's router, or this process as that router."""
    zenoh = import_zenoh()
    conf = _config(zenoh, _SESSION, "ZENOH_SESSION_CONFIG_URI")
    _add_endpoints(conf, "connect/endpoints", [*connect, *_env_list("ROBOMODEL_CONNECT")])
    _add_endpoints(conf, "listen/endpoints", [*listen, *_env_list("ROBOMODEL_LISTEN")])
    try:
        session = zenoh.open(conf)
    except Exception as exc:
        raise ZenohConfigError(f"cannot open a Zenoh session: {exc}") from None
    attempts = check_attempts()
    if attempts is None or _is_router(conf):
        return OpenedSession(session, _is_router(conf))
    connect_to = _endpoints(conf, "connect/endpoints")
    local = [e for e in connect_to if e.startswith(_LOOPBACK_HOSTS)]
    if wait_for_router(session, attempts, local):
        return OpenedSession(session, False, tuple(connect_to))
    if not local:
        log.warning(
            "no Zenoh router answers at %s; peers on other machines will not be found",
            ", ".join(connect_to) or "(no connect endpoint)",
        )
        return OpenedSession(session, False)
    router = start_router(local[0])

    def started() -> bool:
        # The session's connect retry (250 ms to 1 s) links it to the new router; a session
        # used before then sees an empty graph (a second launch would host a parameter server
        # of its own). The router writes its record just after it listens, so a session can
        # link before the record is there: wait for both, so that `robomodel router --stop`
        # finds the router as soon as this returns (unless the router ended, e.g. lost its port).
        linked = bool(list(session.info.routers_zid()))
        return linked and (router.poll() is not None or read_record(local[0]) is not None)

    deadline = time.monotonic() + ROUTER_START_WAIT_S
    while not started() and time.monotonic() < deadline:
        time.sleep(0.01)
    if not list(session.info.routers_zid()):
        log.warning("the Zenoh router started on %s did not answer; see its log", local[0])
    return OpenedSession(session, False, tuple(connect_to), started_router=True)


def _is_router(conf: Any) -> bool:
    try:
        return bool(json.loads(conf.get_json("mode")) == "router")
    except Exception:
        return False
