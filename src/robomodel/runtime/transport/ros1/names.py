"""ROS 1 names as rosgraph.names resolves them and roscpp validates them, and the addresses a
node advertises and listens on."""

from __future__ import annotations

import contextlib
import ipaddress
import os
import re
import socket
import urllib.parse

from robomodel.errors import RobomodelError

__all__ = [
    "DEFAULT_MASTER_URI",
    "MAX_NAME_BYTES",
    "Ros1NameError",
    "advertised_host",
    "bind_host",
    "canonical",
    "check_name",
    "check_uri",
    "http_uri",
    "is_loopback",
    "listen_host",
    "master_bind_host",
    "master_uri",
    "namespace_of",
    "resolve",
    "split_uri",
]

DEFAULT_MASTER_URI = "http://localhost:11311/"
# rosmaster and roscpp bound no name; names are short in practice, and a bound keeps a peer's
# 10 MB topic name out of the master's memory. URIs (caller and service APIs) get the same bound.
MAX_NAME_BYTES = 1024
# rosmaster's validators (valid_name_validator_resolved) refuse ':' and ' ' in a name; roscpp's
# ros::names::validate is stricter, but rospy and the tools register names it refuses (rosparam's
# caller_id is /rosparam-PID). robomodel refuses what rosmaster does, all whitespace and control
# characters too (a name is printed by every listing).
_ILLEGAL = re.compile(r"[:\s\x00-\x1f\x7f-\x9f]")
_LOOPBACK_NAMES = {"localhost": "127.0.0.1", "ip6-localhost": "::1", "ip6-loopback": "::1"}


class Ros1NameError(RobomodelError):
    """A graph name or URI from a peer that is not one ROS accepts, or is longer than the bound."""


def check_name(name: object, what: str) -> str:
    """``name`` if it is a ROS graph name as rosmaster takes one (no ':', no whitespace; no
    control characters either) within ``MAX_NAME_BYTES`` characters."""
    if not isinstance(name, str) or not name:
        raise Ros1NameError(f"{what} must be a non-empty string")
    if len(name) > MAX_NAME_BYTES:
        raise Ros1NameError(f"{what} is {len(name)} characters; at most {MAX_NAME_BYTES}")
    if _ILLEGAL.search(name):
        raise Ros1NameError(
            f"{what} {name[:80]!r} is not a ROS name (no ':', whitespace or control characters)"
        )
    return name


def check_uri(uri: object, what: str) -> str:
    """``uri`` if it is an http:// or rosrpc:// URI with a host and port (rosmaster's is_api
    checks the scheme only; a URI without a port cannot be called back either)."""
    if not isinstance(uri, str) or len(uri) > MAX_NAME_BYTES:
        raise Ros1NameError(f"{what} must be a URI of at most {MAX_NAME_BYTES} characters")
    try:
        split_uri(uri)
    except RobomodelError:
        raise Ros1NameError(f"{what} {uri[:80]!r} is not an http:// or rosrpc:// URI") from None
    return uri


def canonical(name: str) -> str:
    """``//a///b/`` -> ``/a/b`` (rosgraph's canonicalize_name)."""
    if not name or name == "/":
        return name
    leading = "/" if name.startswith("/") else ""
    return leading + "/".join(part for part in name.split("/") if part)


def namespace_of(name: str) -> str:
    """The namespace of a node or topic name, with a trailing slash (``/a/b`` -> ``/a/``)."""
    parent, slash, _ = canonical(name).rpartition("/")
    return parent + slash or "/"  # "a" is in the global namespace, as rosgraph has it


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
    """``http://host:port/`` (or ``rosrpc://host:port``) -> (host, port). An IPv6 host is
    bracketed (``http://[::1]:11311/``), or bare as rospy writes it for ``ROS_IP=::1``."""
    try:
        parsed = urllib.parse.urlparse(uri)
        host, port = parsed.hostname, parsed.port
    except ValueError:
        parsed, host, port = urllib.parse.urlparse("x:"), None, None
        scheme, _, rest = uri.partition("://")
        netloc = rest.split("/", 1)[0]
        if netloc.count(":") > 1 and "[" not in netloc:  # rospy's http://::1:port/
            bare, _, digits = netloc.rpartition(":")
            with contextlib.suppress(ValueError):  # not an IPv6 address either (http://a:b:c/)
                parsed = urllib.parse.urlparse(f"{scheme}://[{bare}]:{digits}/")
                host, port = parsed.hostname, int(digits) if digits.isdigit() else None
    if parsed.scheme not in ("http", "rosrpc") or not host or port is None:
        raise RobomodelError(
            f"'{uri[:200]}' is not a ROS 1 URI; use http://HOST:PORT/ (ROS_MASTER_URI), "
            "http://[IPV6]:PORT/ or rosrpc://HOST:PORT"
        )
    return host, port


def http_uri(host: str, port: int, scheme: str = "http") -> str:
    """``http://host:port/`` (``rosrpc://host:port``), an IPv6 host bracketed."""
    shown = f"[{host}]" if ":" in host else host
    return f"{scheme}://{shown}:{port}" + ("/" if scheme == "http" else "")


def advertised_host() -> str:
    """The host other nodes reach this process at: ``ROS_IP``, ``ROS_HOSTNAME``, else
    127.0.0.1 (roscpp's order, with loopback instead of the machine's name by default)."""
    return os.environ.get("ROS_IP") or os.environ.get("ROS_HOSTNAME") or "127.0.0.1"


def _addresses(host: str) -> list[str]:
    """``host``'s addresses: itself when it is an IP literal, else what it resolves to."""
    try:
        return [str(ipaddress.ip_address(host.strip("[]")))]
    except ValueError:
        pass
    try:
        return list(dict.fromkeys(str(a[4][0]) for a in socket.getaddrinfo(host, None)))
    except (OSError, UnicodeError):
        return []


def is_loopback(host: str) -> bool:
    """Whether ``host`` names this machine's loopback only: 127.0.0.0/8, ::1, or a name that
    resolves to nothing else (``localhost``, ``ip6-localhost`` even where it does not resolve)."""
    addresses = _addresses(host)
    if not addresses:
        return host.lower() in _LOOPBACK_NAMES
    return all(ipaddress.ip_address(a.split("%")[0]).is_loopback for a in addresses)


def listen_host(host: str) -> str:
    """The address to listen on for peers that reach this process at ``host``: that loopback
    address when ``host`` is loopback (IPv4 preferred for a name with both), else every
    interface of its family ("::" also takes IPv4 where the system allows dual stack)."""
    addresses = _addresses(host)
    if is_loopback(host):
        if not addresses:
            return _LOOPBACK_NAMES[host.lower()]
        return next((a for a in addresses if ":" not in a), addresses[0])
    return "::" if addresses and all(":" in a for a in addresses) else "0.0.0.0"


def bind_host() -> str:
    """Where this process listens: loopback only, unless ``ROS_IP``/``ROS_HOSTNAME`` name an
    address other machines use, then every interface (as roscpp binds)."""
    if os.environ.get("ROS_IP") or os.environ.get("ROS_HOSTNAME"):
        return listen_host(advertised_host())
    return "127.0.0.1"


def master_bind_host(uri: str) -> str:
    """Where a master serving ``uri`` listens: every interface when ``ROS_IP``/``ROS_HOSTNAME``
    name an address others use (as :func:`bind_host`), else where its URI points (peers find it
    by ``ROS_MASTER_URI``): the loopback address it names (``http://[::1]:11311/`` needs ::1,
    ``http://localhost:11311/`` 127.0.0.1 even with ``ROS_IP=127.0.0.2``), or every interface
    for a URI with an address others use."""
    mine, theirs = bind_host(), listen_host(split_uri(uri)[0])
    if mine in ("0.0.0.0", "::"):
        return "::" if ":" in theirs else mine  # "::" takes IPv4 too
    return theirs
