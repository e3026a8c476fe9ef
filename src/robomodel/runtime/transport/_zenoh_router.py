"""Finding the router, and robomodel's own router that outlives the process that started it.

- ``ZENOH_ROUTER_CHECK_ATTEMPTS`` as rmw_zenoh reads it (``zenoh_router_check_attempts`` in
  ``zenoh_config.cpp``, the loop in ``rmw_context_impl_s.cpp``, Jazzy 0.2.10): unset or empty
  is one check; ``strtoll`` of the text (so ``abc`` is 0) above zero is that many checks one
  second apart, 0 checks for ever, below zero skips the check.
- When the checks find no router and the configuration names one on this machine (a loopback
  endpoint, by default ``tcp/localhost:7447``), a ``robomodel router`` is started for it, like
  ``ros2 daemon``: a process of its own session (no terminal's Ctrl-C reaches it), its output in
  a log file, listening on that loopback endpoint only. It ends once no session has been linked
  to it for ``ROUTER_IDLE_S`` (``robomodel router --idle-exit``), or on ``robomodel router
  --stop``. Each router robomodel runs records its pid and Zenoh id in
  ``<state dir>/router-<port>.json`` (state dir: ``$XDG_RUNTIME_DIR/robomodel``, else
  ``/tmp/robomodel-<uid>``).
"""

from __future__ import annotations

import contextlib
import json
import os
import signal
import socket
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from robomodel.runtime.transport._zenoh_common import log

__all__ = [
    "ROUTER_IDLE_S",
    "RouterRecord",
    "check_attempts",
    "endpoint_port",
    "listening",
    "read_record",
    "record_path",
    "start_router",
    "stop_router",
    "wait_for_router",
]

ROUTER_IDLE_S = 60.0
_CHECK_PERIOD_S = 1.0  # rmw_context_impl_s.cpp: sleep_time
_LINK_WAIT_S = 3.0  # a router that listens links up within this on a loaded machine


def check_attempts() -> int | None:
    """How many times to look for a router: None to skip, 0 for ever (rmw_zenoh's rules)."""
    text = os.environ.get("ZENOH_ROUTER_CHECK_ATTEMPTS", "")
    if text == "":
        return 1
    rest = text.lstrip(" \t\n\v\f\r")  # strtoll(text, nullptr, 10)
    sign = -1 if rest[:1] == "-" else 1
    rest = rest[1:] if rest[:1] in ("+", "-") else rest
    digits = len(rest) - len(rest.lstrip("0123456789"))
    value = sign * int(rest[:digits]) if digits else 0
    if value < 0:
        return None
    return value


def endpoint_port(endpoint: str) -> int | None:
    """The port of ``tcp/host:port`` (None when there is none)."""
    _, _, port = endpoint.rpartition(":")
    return int(port) if port.isdigit() else None


def listening(endpoint: str) -> bool:
    """Whether something accepts TCP connections at ``tcp/host:port`` (localhost: 127.0.0.1)."""
    port = endpoint_port(endpoint)
    protocol, _, address = endpoint.partition("/")
    if port is None or protocol != "tcp":
        return False
    host = address.rpartition(":")[0].strip("[]")
    host = "127.0.0.1" if host == "localhost" else host
    try:
        with socket.create_connection((host, port), timeout=0.5):
            return True
    except OSError:
        return False


def _linked(session: Any) -> bool:
    return bool(list(session.info.routers_zid()))


def wait_for_router(session: Any, attempts: int, endpoints: list[str]) -> bool:
    """Check ``attempts`` times (0: for ever), one second apart, for a router; a router that
    already listens at one of ``endpoints`` is given time to link up."""
    tries = 0
    while True:
        if _linked(session):
            return True
        if any(listening(e) for e in endpoints):
            deadline = time.monotonic() + _LINK_WAIT_S
            while time.monotonic() < deadline:
                if _linked(session):
                    return True
                time.sleep(0.01)
        tries += 1
        if attempts and tries >= attempts:
            return False
        if tries == 1:
            log.warning(
                "no Zenoh router answers; waiting for one (ZENOH_ROUTER_CHECK_ATTEMPTS=%s)",
                os.environ.get("ZENOH_ROUTER_CHECK_ATTEMPTS", ""),
            )
        time.sleep(_CHECK_PERIOD_S)


def _state_dir() -> Path:
    runtime = os.environ.get("XDG_RUNTIME_DIR")
    if runtime:
        return Path(runtime) / "robomodel"
    return Path("/tmp") / f"robomodel-{getattr(os, 'getuid', lambda: 0)()}"


def record_path(endpoint: str) -> Path:
    return _state_dir() / f"router-{endpoint_port(endpoint)}.json"


@dataclass(frozen=True, slots=True)
class RouterRecord:
    """A router robomodel runs: its process and Zenoh id, and its listening endpoints."""

    pid: int
    zid: str
    endpoints: tuple[str, ...]

    def write(self) -> None:
        """Written atomically for each endpoint with a port."""
        for endpoint in self.endpoints:
            if endpoint_port(endpoint) is None:
                continue
            path = record_path(endpoint)
            path.parent.mkdir(parents=True, exist_ok=True)
            part = path.with_suffix(f".{os.getpid()}.part")
            part.write_text(json.dumps({"pid": self.pid, "zid": self.zid,
                                        "endpoints": list(self.endpoints)}))  # fmt: skip
            os.replace(part, path)

    def remove(self) -> None:
        for endpoint in self.endpoints:
            record = _read(endpoint)
            if record is not None and record.pid == self.pid:
                with contextlib.suppress(OSError):
                    record_path(endpoint).unlink()


def _alive(pid: int) -> bool:
    """Whether ``pid`` runs (a zombie, ended but not yet reaped by its parent, does not)."""
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    try:
        with open(f"/proc/{pid}/stat", "rb") as stat:
            return stat.read().rsplit(b")", 1)[1].split()[0] != b"Z"
    except (OSError, IndexError):
        return True  # no /proc: kill(0) is the best answer


def _read(endpoint: str) -> RouterRecord | None:
    try:
        data = json.loads(record_path(endpoint).read_text())
        return RouterRecord(int(data["pid"]), str(data["zid"]), tuple(data["endpoints"]))
    except (OSError, ValueError, KeyError, TypeError):
        return None


def read_record(endpoint: str) -> RouterRecord | None:
    """The router robomodel runs on ``endpoint``'s port, if its process is alive."""
    record = _read(endpoint)
    return record if record is not None and _alive(record.pid) else None


def start_router(endpoint: str, idle_s: float = ROUTER_IDLE_S) -> subprocess.Popen[bytes]:
    """A detached ``robomodel router`` on ``endpoint`` (see the module docstring)."""
    directory = _state_dir()
    directory.mkdir(parents=True, exist_ok=True)
    log_path = directory / f"router-{endpoint_port(endpoint)}.log"
    command = [sys.executable, "-m", "robomodel.cli.main", "router", "--listen", endpoint,
               "--idle-exit", f"{idle_s:g}"]  # fmt: skip
    with open(log_path, "ab") as out:
        process = subprocess.Popen(
            command,
            stdin=subprocess.DEVNULL,
            stdout=out,
            stderr=out,
            start_new_session=True,  # its own session and process group, as a daemon
            close_fds=True,
        )
    log.info("started a Zenoh router (pid %d) on %s; log in %s", process.pid, endpoint, log_path)
    return process


def stop_router(endpoint: str, timeout_s: float = 10.0) -> RouterRecord | None:
    """End the router robomodel runs on ``endpoint``'s port; None when there is none."""
    record = read_record(endpoint)
    if record is None:
        return None
    with contextlib.suppress(ProcessLookupError):
        os.kill(record.pid, signal.SIGTERM)
    deadline = time.monotonic() + timeout_s
    while _alive(record.pid) and time.monotonic() < deadline:
        with contextlib.suppress(ChildProcessError):
            os.waitpid(record.pid, os.WNOHANG)  # our own child: reap it
        time.sleep(0.02)
    if _alive(record.pid):
        with contextlib.suppress(ProcessLookupError):
            os.kill(record.pid, signal.SIGKILL)
    record.remove()
    return record
