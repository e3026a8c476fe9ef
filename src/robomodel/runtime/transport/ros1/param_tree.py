"""rosmaster's parameter tree: getting a namespace returns a dict, setting a dict replaces the
whole namespace, names are leaves (``rosparam list``) and ``searchParam`` looks upwards.

The ROS 1 master serves it over XML-RPC; ``robomodel launch`` on the other buses serves it as
a service of a hidden node (robomodel.launch.param_server).
"""

from __future__ import annotations

import threading
from typing import Any

from robomodel.errors import RobomodelError
from robomodel.runtime.transport.ros1.names import MAX_NAME_BYTES
from robomodel.runtime.transport.ros1.param_bounds import (
    DICT_BYTES,
    MAX_KEY_DEPTH,
    MAX_TREE_BYTES,
    MAX_VALUE_BYTES,
    ParamBoundError,
    copy_tree,
    expand_measured,
    tree_size,
)

__all__ = ["ParamServerError", "ParamTree", "split_name"]


class ParamServerError(RobomodelError):
    """A parameter that is not set, or a server that cannot be reached."""


def split_name(name: str) -> list[str]:
    return [p for p in name.split("/") if p]


def _checked_parts(name: str) -> list[str]:
    """``name``'s parts, within the name's length and depth bounds."""
    if len(name) > MAX_NAME_BYTES:
        raise ParamServerError(
            f"parameter name [{name[:80]}...] is {len(name)} characters; at most {MAX_NAME_BYTES}"
        )
    parts = split_name(name)
    if len(parts) > MAX_KEY_DEPTH:
        raise ParamServerError(
            f"parameter name [{name[:80]}...] has {len(parts)} levels; at most {MAX_KEY_DEPTH}"
        )
    return parts


class ParamTree:
    """rosmaster's parameter tree (paramserver.py), thread-safe and bounded.

    Each value is expanded into a plain tree when set (see param_bounds), at most
    ``max_value_bytes``; the whole tree holds at most ``max_tree_bytes``, the names of the
    namespaces a set creates included. A name has at most ``MAX_NAME_BYTES`` characters and
    ``MAX_KEY_DEPTH`` levels. Past any of these, the set is refused with a ParamServerError
    that reaches the client. Walks over the tree are loops, so no tree is too deep to read.
    """

    def __init__(
        self, *, max_value_bytes: int = MAX_VALUE_BYTES, max_tree_bytes: int = MAX_TREE_BYTES
    ) -> None:
        self._tree: dict[str, Any] = {}
        self._lock = threading.Lock()
        self._size = 0
        self._max_value_bytes = max_value_bytes
        self._max_tree_bytes = max_tree_bytes

    def set(self, name: str, value: Any) -> None:
        parts = _checked_parts(name)
        try:
            value, added = expand_measured(value, what=f"[{name}]", limit=self._max_value_bytes)
        except ParamBoundError as exc:
            raise ParamServerError(str(exc)) from None
        with self._lock:
            if not parts:
                if not isinstance(value, dict):
                    raise ParamServerError("cannot set root of parameter tree to non-dictionary")
                self._check_total(added - self._size, name)
                self._tree, self._size = value, added
                return
            change = added + 8 + len(parts[-1]) + self._path_change(parts)
            self._check_total(change, name)
            node = self._tree
            for part in parts[:-1]:
                child = node.get(part)
                if not isinstance(child, dict):
                    child = node[part] = {}
                node = child
            node[parts[-1]] = value
            self._size += change

    def _path_change(self, parts: list[str]) -> int:
        """The size setting ``parts`` adds besides the value and its own key: the namespaces it
        creates, less what it replaces (the old value, or a leaf on the way)."""
        node: Any = self._tree
        for index, part in enumerate(parts):
            if part not in node:
                return sum(8 + len(p) + DICT_BYTES for p in parts[index:-1])
            child = node[part]
            if index == len(parts) - 1:
                return -(tree_size(child) + 8 + len(part))
            if not isinstance(child, dict):  # the leaf becomes a namespace
                created = sum(8 + len(p) + DICT_BYTES for p in parts[index + 1 : -1])
                return created + DICT_BYTES - tree_size(child)
            node = child
        return 0

    def _check_total(self, change: int, name: str) -> None:
        if self._size + change > self._max_tree_bytes:
            raise ParamServerError(
                f"setting [{name}] would make the parameter server hold more than "
                f"{self._max_tree_bytes / 2**20:.0f} MiB; delete parameters first"
            )

    def _find(self, name: str) -> Any:
        node: Any = self._tree
        for part in split_name(name):
            if not isinstance(node, dict) or part not in node:
                raise ParamServerError(f"Parameter [{name}] is not set")
            node = node[part]
        return node

    def get(self, name: str) -> Any:
        with self._lock:
            return copy_tree(self._find(name))

    def has(self, name: str) -> bool:
        with self._lock:
            try:
                self._find(name)
            except ParamServerError:
                return False
        return True

    def delete(self, name: str) -> None:
        parts = split_name(name)
        with self._lock:
            if not parts:
                self._tree, self._size = {}, 0
                return
            node = self._tree
            for part in parts[:-1]:
                node = node.get(part) if isinstance(node, dict) else None  # type: ignore[assignment]
                if not isinstance(node, dict):
                    raise ParamServerError(f"Parameter [{name}] is not set")
            if parts[-1] not in node:
                raise ParamServerError(f"Parameter [{name}] is not set")
            removed = tree_size(node[parts[-1]]) + 8 + len(parts[-1])
            self._size = max(0, self._size - removed)
            del node[parts[-1]]

    def names(self) -> list[str]:
        """Every leaf parameter's full name, sorted (rosparam list)."""
        out: list[str] = []
        with self._lock:
            stack = [("/" + key, value) for key, value in self._tree.items()]
            while stack:  # a loop: no tree is too deep for it
                prefix, node = stack.pop()
                if isinstance(node, dict) and node:
                    stack.extend((f"{prefix}/{key}", child) for key, child in node.items())
                else:
                    out.append(prefix)
        return sorted(out)

    def search(self, namespace: str, key: str) -> str | None:
        """rosmaster's searchParam: ``key`` in ``namespace``, then in each parent."""
        first = split_name(key)[0] if split_name(key) else key
        parts = split_name(namespace)
        for depth in range(len(parts), -1, -1):
            base = "/" + "/".join(parts[:depth]) if depth else ""
            if self.has(f"{base}/{first}"):
                rest = "/".join(split_name(key)[1:])
                return f"{base}/{first}" + (f"/{rest}" if rest else "")
        return None
