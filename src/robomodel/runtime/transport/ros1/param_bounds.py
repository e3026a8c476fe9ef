"""Bounds of a parameter server: one value, the whole tree, and YAML aliases expanded once.

A YAML document with aliases (``&a [*b, *b, ...]``, a "billion laughs") loads as a small graph
of shared references but is a huge tree: every get would serialise the whole expansion. So a
value is expanded into a plain tree when it is set (or when a ``<rosparam>`` document is
loaded), under a bound, and refused with a clear error past it; a get then costs what the
stored tree costs. Sizes are counted as the serialised value would be: the bytes of each string
or binary, 8 per number, boolean or container entry.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from robomodel.errors import RobomodelError

__all__ = [
    "MAX_DEPTH",
    "MAX_TREE_BYTES",
    "MAX_VALUE_BYTES",
    "ParamBoundError",
    "expand_bounded",
    "tree_size",
]

MAX_VALUE_BYTES = 32 * 1024 * 1024  # one value (a robot_description is well under 2 MiB)
MAX_TREE_BYTES = 256 * 1024 * 1024  # the whole server
MAX_DEPTH = 100  # nesting of dicts and lists


class ParamBoundError(RobomodelError):
    """A parameter value over the size or nesting bound."""


class _Budget:
    __slots__ = ("left", "limit", "what")

    def __init__(self, limit: int, what: str) -> None:
        self.left = limit
        self.limit = limit
        self.what = what

    def spend(self, units: int) -> None:
        self.left -= units
        if self.left < 0:
            raise ParamBoundError(
                f"{self.what} is larger than {self.limit / 2**20:.0f} MiB once expanded "
                "(YAML aliases repeating a block?); parameters are bounded to keep the server's "
                "memory bounded"
            )


def _leaf_size(value: Any) -> int:
    if isinstance(value, str):
        return len(value)  # characters: a close bound of the UTF-8 bytes for the sizes here
    if isinstance(value, bytes | bytearray):
        return len(value)
    data = getattr(value, "data", None)  # launch's Binary
    return len(data) if isinstance(data, bytes | bytearray) else 8


def _expand(value: Any, budget: _Budget, depth: int) -> Any:
    if depth > MAX_DEPTH:
        raise ParamBoundError(
            f"{budget.what} is nested deeper than {MAX_DEPTH} levels of dictionaries and lists"
        )
    if isinstance(value, Mapping):
        out: dict[str, Any] = {}
        for key, item in value.items():
            budget.spend(8 + len(str(key)))
            out[str(key) if not isinstance(key, str) else key] = _expand(item, budget, depth + 1)
        return out
    if isinstance(value, list | tuple):
        budget.spend(8)
        return [_expand(item, budget, depth + 1) for item in value]
    budget.spend(_leaf_size(value))
    return value


def _measure(value: Any, memo: dict[int, int], open_ids: set[int], depth: int, what: str) -> int:
    """The expanded size, each shared container measured once (memo by id)."""
    if not isinstance(value, Mapping | list | tuple):
        return _leaf_size(value)
    key = id(value)
    if key in memo:
        return memo[key]
    if key in open_ids:
        raise ParamBoundError(f"{what} contains itself (a recursive YAML alias)")
    if depth > MAX_DEPTH:
        raise ParamBoundError(
            f"{what} is nested deeper than {MAX_DEPTH} levels of dictionaries and lists"
        )
    open_ids.add(key)
    if isinstance(value, Mapping):
        size = sum(
            8 + len(str(k)) + _measure(v, memo, open_ids, depth + 1, what) for k, v in value.items()
        )
    else:
        size = 8 + sum(_measure(v, memo, open_ids, depth + 1, what) for v in value)
    open_ids.discard(key)
    memo[key] = size
    return size


def expand_bounded(value: Any, *, what: str = "the value", limit: int = MAX_VALUE_BYTES) -> Any:
    """A plain tree copy of ``value`` (shared references copied apart), or ParamBoundError.

    The expanded size is measured first, each shared block once, so an alias bomb is refused
    in the time it takes to read it, not to expand it. Dict keys become strings, tuples
    lists, as XML-RPC and YAML give them.
    """
    try:
        size = _measure(value, {}, set(), 0, what)
        if size > limit:
            _Budget(limit, what).spend(size)
        return _expand(value, _Budget(limit, what), 0)
    except RecursionError:
        raise ParamBoundError(f"{what} is nested too deeply") from None


def tree_size(value: Any) -> int:
    """The size of a plain tree (as :func:`expand_bounded` counts it)."""
    if isinstance(value, dict):
        return sum(8 + len(k) + tree_size(v) for k, v in value.items())
    if isinstance(value, list):
        return 8 + sum(tree_size(v) for v in value)
    return _leaf_size(value)
