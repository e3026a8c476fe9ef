"""ROS 1 graph-resource names, as ``rosgraph.names`` handles them (the launch loader's rules)."""

from __future__ import annotations

import os
import re
import socket

__all__ = [
    "anonymous_name",
    "canonicalize_name",
    "is_global",
    "is_legal_name",
    "is_private",
    "make_global_ns",
    "namespaces_of",
    "ns_join",
]

SEP = "/"
PRIV = "~"
_LEGAL = re.compile(r"^[~/]?([a-zA-Z]\w*/)*[a-zA-Z]\w*/?$|^$|^/$|^~$")


def is_private(name: str) -> bool:
    return bool(name) and name[0] == PRIV


def is_global(name: str) -> bool:
    return bool(name) and name[0] == SEP


def ns_join(ns: str, name: str) -> str:
    """Join a namespace and a name; ``~private`` and ``/global`` names are returned as they are."""
    if is_private(name) or is_global(name):
        return name
    if ns == PRIV:
        return PRIV + name
    if not ns:
        return name
    return ns + name if ns[-1] == SEP else ns + SEP + name


def make_global_ns(name: str) -> str:
    """``name`` as a global namespace with a trailing ``/`` (``a`` -> ``/a/``)."""
    if is_private(name):
        raise ValueError(f"cannot turn [{name}] into a global name")
    if not is_global(name):
        name = SEP + name
    return name if name[-1] == SEP else name + SEP


def canonicalize_name(name: str) -> str:
    """Remove doubled and trailing slashes (``/a//b/`` -> ``/a/b``)."""
    if not name or name == SEP:
        return name
    parts = "/".join(x for x in name.split(SEP) if x)
    return SEP + parts if name[0] == SEP else parts


def is_legal_name(name: str | None) -> bool:
    """A legal ROS graph name (letters, digits, ``_``, ``/``; a letter first in each part)."""
    if name is None:
        return False
    if name == "":
        return True
    return bool(re.fullmatch(r"[~/]?([A-Za-z][\w]*)?(/[A-Za-z][\w]*)*/?", name)) and (
        "//" not in name
    )


def namespaces_of(name: str) -> list[str]:
    """The parent namespaces of a name: ``/a/b/c`` -> ``['/', '/a/', '/a/b/']``."""
    out = [SEP]
    parts = [p for p in name.split(SEP) if p][:-1]
    for i in range(len(parts)):
        out.append(SEP + SEP.join(parts[: i + 1]) + SEP)
    return out


def anonymous_name(base: str, counter: int) -> str:
    """A ROS-legal anonymous name, as ``rosgraph.names.anonymous_name`` builds it (base, host,
    pid, then a number: here a counter, so one launch run is reproducible)."""
    name = f"{base}_{socket.gethostname()}_{os.getpid()}_{counter}"
    return name.replace(".", "_").replace("-", "_").replace(":", "_")
