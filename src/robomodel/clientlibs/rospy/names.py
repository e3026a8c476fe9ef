"""ROS 1 names as rospy resolves them: the command line's remappings (``from:=to``,
``__name:=``, ``__ns:=``, ``_param:=value``), private ``~names``, relative names in the node's
namespace, and remapping of the resolved name (rosgraph.names' rules)."""

from __future__ import annotations

import os
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

__all__ = [
    "CommandLine",
    "canonicalize_name",
    "namespace_of",
    "parse_command_line",
    "resolve",
    "strip_remappings",
]

REMAP = ":="
SPECIAL = ("__name", "__ns", "__log", "__ip", "__hostname", "__master")
_SEPS = re.compile("/+")


@dataclass(frozen=True)
class CommandLine:
    """The ROS part of a node's command line."""

    remappings: Mapping[str, str] = field(default_factory=dict)  # names as written
    special: Mapping[str, str] = field(default_factory=dict)  # __name, __ns, ...
    params: Mapping[str, Any] = field(default_factory=dict)  # _x:=v, v read as YAML


def parse_command_line(argv: Sequence[str]) -> CommandLine:
    """The remappings, special keys and private parameters of ``argv`` (rospy's reading: a
    ``_name:=value`` is a parameter ``~name`` whose value is read as a YAML scalar)."""
    remappings: dict[str, str] = {}
    special: dict[str, str] = {}
    params: dict[str, Any] = {}
    for arg in argv:
        if REMAP not in arg:
            continue
        parts = [part.strip() for part in arg.split(REMAP)]
        if len(parts) != 2 or not parts[0] or not parts[1]:
            continue  # rosgraph skips what is not 'a:=b'
        source, target = parts
        if source in SPECIAL:
            special[source] = target
        elif source.startswith("__"):
            continue  # another special key (__log etc. that rospy ignores too)
        elif source.startswith("_"):
            import yaml

            try:
                params[source[1:]] = yaml.safe_load(target)
            except yaml.YAMLError:
                params[source[1:]] = target
        else:
            remappings[source] = target
    return CommandLine(remappings, special, params)


def strip_remappings(argv: Sequence[str]) -> list[str]:
    """``argv`` without its ``a:=b`` arguments (rospy's ``myargv``)."""
    return [arg for arg in argv if REMAP not in arg]


def canonicalize_name(name: str) -> str:
    """One ``/`` between tokens, none at the end (``//a//b/`` -> ``/a/b``)."""
    if not name or name == "/":
        return name
    name = _SEPS.sub("/", name)
    return name.rstrip("/") if name != "/" else name


def namespace_of(name: str) -> str:
    """The namespace of a global name, with its trailing ``/`` (``/a/b`` -> ``/a/``)."""
    if not name or name == "/":
        return "/"
    head = name.rstrip("/").rsplit("/", 1)[0]
    return head + "/" if head else "/"


def global_namespace(namespace: str) -> str:
    """``ns`` as a global namespace with a trailing ``/`` (``a`` -> ``/a/``)."""
    namespace = canonicalize_name("/" + namespace.strip())
    return namespace if namespace == "/" else namespace + "/"


def resolve(name: str, caller_id: str, remappings: Mapping[str, str] | None = None) -> str:
    """``name`` resolved for node ``caller_id``: global names as they are, ``~x`` under the
    node, others in its namespace; then the remapping of the resolved name, if any."""
    if not name:
        return namespace_of(caller_id)
    name = canonicalize_name(name)
    if name.startswith("/"):
        resolved = name
    elif name.startswith("~"):
        resolved = canonicalize_name(caller_id + "/" + name[1:])
    else:
        resolved = namespace_of(caller_id) + name
    if remappings and resolved in remappings:
        return remappings[resolved]
    return resolved


def resolve_remappings(remappings: Mapping[str, str], caller_id: str) -> dict[str, str]:
    """Both sides of every remapping resolved for ``caller_id``, as rospy does at init."""
    return {
        resolve(source, caller_id): resolve(target, caller_id)
        for source, target in remappings.items()
    }


def namespace_from(special: Mapping[str, str]) -> str:
    """The node's namespace: ``__ns:=``, else ``ROS_NAMESPACE``, else ``/``."""
    return global_namespace(special.get("__ns") or os.environ.get("ROS_NAMESPACE", ""))
