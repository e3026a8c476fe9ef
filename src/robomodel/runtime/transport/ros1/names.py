"""ROS 1 names as rosgraph.names resolves them, and the addresses a node advertises."""

from __future__ import annotations

import os
import urllib.parse

from robomodel.errors import RobomodelError

__all__ = [
    "DEFAULT_MASTER_URI",
    "advertised_host",
    "bind_host",
    "canonical",
    "master_uri",
    "namespace_of",
    "resolve",
    "split_uri",
]

DEFAULT_MASTER_URI = "http://localhost:11311/"


def canonical(name: str) -> str:
    """``//a///b/`` -> ``/a/b`` (rosgraph's canonicalize_name)."""
    if not name or name == "/":
        return name
    leading = "/" if name.startswith("/") else ""
    return leading + "/".join(part for part in name.split("/") if part)


def namespace_of(name: str) -> str:
    """The namespace of a node or topic name, with a trailing slash (``/a/b`` -> ``/a/``)."""
    name = canonical(name)
    if not name or name == "/":
        return "/"
    parent = name.rsplit("/", 1)[0]
    return parent + "/" if parent else "/"


def resolve(name: str, caller_id: str) -> str:
    """rosgraph.names.resolve_name: global as is, ``~x`` under the caller, else in its
    namespace."""
    if not name:
        return namespace_of(caller_id)
    name = canonical(name)
    if name.startswith("/"):
        return name
    if name.startswith("~"):
        return canonical(f"{caller_id}/{name[1:]}")
    return canonical(namespace_of(caller_id) + name)


def master_uri(explicit: str | None = None) -> str:
    """The master's URI: ``explicit``, else ``ROS_MASTER_URI``, else http://localhost:11311/."""
    uri = explicit or os.environ.get("ROS_MASTER_URI") or DEFAULT_MASTER_URI
    split_uri(uri)  # validates
    return uri


def split_uri(uri: str) -> tuple[str, int]:
    """``http://host:port/`` (or ``rosrpc://host:port``) -> (host, port)."""
    parsed = urllib.parse.urlparse(uri)
    try:
        port = parsed.port
    except ValueError:
        port = None
    if parsed.scheme not in ("http", "rosrpc") or not parsed.hostname or port is None:
        raise RobomodelError(
            f"'{uri}' is not a ROS 1 URI; use http://HOST:PORT/ (ROS_MASTER_URI) or "
            "rosrpc://HOST:PORT"
        )
    return parsed.hostname, port


def advertised_host() -> str:
    """The host other nodes reach this process at: ``ROS_IP``, ``ROS_HOSTNAME``, else
    127.0.0.1 (roscpp's order, with loopback instead of the machine's name by default)."""
    return os.environ.get("ROS_IP") or os.environ.get("ROS_HOSTNAME") or "127.0.0.1"


def bind_host() -> str:
    """Where this process listens: loopback only, unless ``ROS_IP``/``ROS_HOSTNAME`` name an
    address other machines use, then every interface (as roscpp binds)."""
    if os.environ.get("ROS_IP") or os.environ.get("ROS_HOSTNAME"):
        host = advertised_host()
        return "127.0.0.1" if host in ("localhost", "127.0.0.1") else "0.0.0.0"
    return "127.0.0.1"
