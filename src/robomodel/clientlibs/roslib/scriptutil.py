"""``roslib.scriptutil``: ``script_resolve_name`` as roslib has it (``ROS_NAMESPACE``, no
remappings); ``get_master`` and ``get_param_server`` (XML-RPC proxies of the master) raise
NotImplementedError naming themselves. ros_tutorials' test nodes import this module."""

from __future__ import annotations

import os
from typing import NoReturn

__all__ = ["get_master", "get_param_server", "script_resolve_name"]


def _namespace() -> str:
    """``ROS_NAMESPACE`` as a global namespace with a trailing ``/`` (``/`` by default)."""
    parts = [p for p in os.environ.get("ROS_NAMESPACE", "").split("/") if p]
    return "/" + "".join(p + "/" for p in parts)


def script_resolve_name(script_name: str, name: str) -> str:
    """``name`` resolved for the script ``script_name``: ``/a`` stays, ``~a`` goes under the
    script (``/ns/script/a``), ``a`` under ``ROS_NAMESPACE``; ``""`` is the namespace."""
    if not name:
        return _namespace()
    if name.startswith("/"):
        return name
    if name.startswith("~"):
        return f"{_namespace()}{script_name}/{name[1:]}"
    return _namespace() + name


def get_master() -> NoReturn:
    raise NotImplementedError(
        "roslib.scriptutil.get_master() (the master's XML-RPC proxy) is not offered by robomodel"
    )


def get_param_server() -> NoReturn:
    raise NotImplementedError(
        "roslib.scriptutil.get_param_server() (the parameter server's XML-RPC proxy) is not"
        " offered by robomodel"
    )
