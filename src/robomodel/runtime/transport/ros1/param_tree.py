"""rosmaster's parameter tree: getting a namespace returns a dict, setting a dict replaces the
whole namespace, names are leaves (``rosparam list``) and ``searchParam`` looks upwards.

The ROS 1 master serves it over XML-RPC; ``robomodel launch`` on the other buses serves it as
the ``/rosmaster`` service (robomodel.launch.param_server).
"""

from __future__ import annotations

import copy
import threading
from collections.abc import Mapping
from typing import Any

from robomodel.errors import RobomodelError

__all__ = ["ParamServerError", "ParamTree", "split_name"]


class ParamServerError(RobomodelError):
    """A parameter that is not set, or a server that cannot be reached."""


def split_name(name: str) -> list[str]:
    return [p for p in name.split("/") if p]


class ParamTree:
    """rosmaster's parameter tree (paramserver.py), thread-safe."""

    def __init__(self) -> None:
        self._tree: dict[str, Any] = {}
        self._lock = threading.Lock()

    def set(self, name: str, value: Any) -> None:
        parts = split_name(name)
        with self._lock:
            if not parts:
                if not isinstance(value, Mapping):
                    raise ParamServerError("cannot set root of parameter tree to non-dictionary")
                self._tree = copy.deepcopy(dict(value))
                return
            node = self._tree
            for part in parts[:-1]:
                child = node.get(part)
                if not isinstance(child, dict):
                    child = node[part] = {}
                node = child
            node[parts[-1]] = copy.deepcopy(dict(value)) if isinstance(value, Mapping) else value

    def get(self, name: str) -> Any:
        node: Any = self._tree
        with self._lock:
            for part in split_name(name):
                if not isinstance(node, dict) or part not in node:
                    raise ParamServerError(f"Parameter [{name}] is not set")
                node = node[part]
            return copy.deepcopy(node)

    def has(self, name: str) -> bool:
        try:
            self.get(name)
        except ParamServerError:
            return False
        return True

    def delete(self, name: str) -> None:
        parts = split_name(name)
        with self._lock:
            if not parts:
                self._tree = {}
                return
            node = self._tree
            for part in parts[:-1]:
                node = node.get(part) if isinstance(node, dict) else None  # type: ignore[assignment]
                if not isinstance(node, dict):
                    raise ParamServerError(f"Parameter [{name}] is not set")
            if parts[-1] not in node:
                raise ParamServerError(f"Parameter [{name}] is not set")
            del node[parts[-1]]

    def names(self) -> list[str]:
        """Every leaf parameter's full name, sorted (rosparam list)."""
        out: list[str] = []

        def walk(prefix: str, node: Any) -> None:
            if isinstance(node, dict) and node:
                for key in node:
                    walk(f"{prefix}/{key}", node[key])
            else:
                out.append(prefix)

        with self._lock:
            for key, value in self._tree.items():
                walk("/" + key, value)
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
