"""The loader's scope as roslaunch keeps it (``roslaunch.loader.LoaderContext``).

Mutable by design (it is the state of one load) and private to the loader: namespace, the
``~private`` params waiting for the next ``<node>``, remaps, env, args and the include rules.
"""

from __future__ import annotations

import copy
from dataclasses import dataclass, field
from typing import Any

from robomodel.launch.ros1.names import (
    PRIV,
    canonicalize_name,
    is_legal_name,
    make_global_ns,
    ns_join,
)

__all__ = ["ContextError", "LoaderContext"]


class ContextError(Exception):
    """A scope rule broken (an arg declared twice, an illegal remap, ...)."""


@dataclass
class LoaderContext:
    ns: str
    filename: str | None
    parent: LoaderContext | None = None
    params: list[tuple[str, Any]] = field(default_factory=list)
    env_args: list[tuple[str, str]] = field(default_factory=list)
    resolve_dict: dict[str, Any] = field(default_factory=dict)
    arg_names: list[str] = field(default_factory=list)
    include_resolve_dict: dict[str, Any] | None = None
    pass_all_args: bool = False
    args_passed: list[str] = field(default_factory=list)
    _remaps: list[tuple[str, str]] = field(default_factory=list)

    def __post_init__(self) -> None:
        self.ns = make_global_ns(self.ns or "/")  # ValueError for "~", as roslaunch

    @property
    def args(self) -> dict[str, str]:
        return self.resolve_dict.setdefault("arg", {})  # type: ignore[no-any-return]

    def add_param(self, key: str, value: Any) -> None:
        """A ``~param`` for the next nodes of this scope (a later one of the same key wins)."""
        self.params[:] = [p for p in self.params if p[0] != key]
        self.params.append((key, value))

    def add_remap(self, source: str, target: str) -> None:
        source, target = canonicalize_name(source), canonicalize_name(target)
        if not source or not target:
            raise ContextError("remap from/to attributes cannot be empty")
        if not is_legal_name(source):
            raise ContextError(f"remap from [{source}] is not a valid ROS name")
        if not is_legal_name(target):
            raise ContextError(f"remap to [{target}] is not a valid ROS name")
        self._remaps = [r for r in self._remaps if r[0] != source]
        self._remaps.append((source, target))

    def remap_args(self) -> list[tuple[str, str]]:
        """Remaps in effect: the parents' (unless overridden here), then this scope's."""
        if self.parent is None:
            return list(self._remaps)
        own = {r[0] for r in self._remaps}
        return [r for r in self.parent.remap_args() if r[0] not in own] + list(self._remaps)

    def add_arg(
        self, name: str, *, value: str | None, default: str | None, doc: str | None
    ) -> None:
        if name in self.arg_names:
            if not self.pass_all_args:
                raise ContextError(f"arg '{name}' has already been declared")
        else:
            self.arg_names.append(name)
        target = (
            self.resolve_dict if self.include_resolve_dict is None else self.include_resolve_dict
        )
        arg_dict: dict[str, str] = target.setdefault("arg", {})
        if value is not None:
            if name in arg_dict and not self.pass_all_args:
                raise ContextError(f"cannot override arg '{name}', which has already been set")
            arg_dict[name] = value
        elif default is not None and name not in arg_dict:
            arg_dict[name] = default
        if not value:
            target.setdefault("arg_doc", {})[name] = (doc, default)

    def child(self, ns: str | None) -> LoaderContext:
        if ns:
            if ns[0] == "/":
                child_ns = ns
            elif ns == PRIV:
                child_ns = PRIV
            else:
                child_ns = ns_join(self.ns, ns)
        else:
            child_ns = self.ns
        return LoaderContext(
            child_ns,
            self.filename,
            parent=self,
            params=self.params or [],  # shared unless empty, exactly as roslaunch's child()
            env_args=list(self.env_args),
            resolve_dict=copy.deepcopy(self.resolve_dict),
            arg_names=list(self.arg_names),
            include_resolve_dict=self.include_resolve_dict,
        )

    def include_child(self, ns: str | None, filename: str) -> LoaderContext:
        ctx = self.child(ns)
        ctx.arg_names = []
        ctx.filename = filename
        ctx.include_resolve_dict = {}
        return ctx

    def process_include_args(self) -> None:
        """roslaunch's ``process_include_args``: the include's <arg value=...> become its args."""
        arg_dict = (self.include_resolve_dict or {}).get("arg", {})
        for name in self.arg_names:
            if name not in arg_dict:
                raise ContextError("include args must have declared values")
        self.args_passed = list(arg_dict)
        self.arg_names = []
        self.resolve_dict = self.include_resolve_dict or {}
        self.include_resolve_dict = None

    def unused_include_args(self) -> list[str]:
        return [a for a in self.args_passed if a not in self.arg_names]
