"""Bounds of a parameter server: one value, the whole tree, and YAML aliases expanded once.

A YAML document with aliases (``&a [*b, *b, ...]``, a "billion laughs") loads as a small graph
of shared references but is a huge tree: every get would serialise the whole expansion. So a
value is expanded into a plain tree when it is set (or when a ``<rosparam>`` document is
loaded), under a bound, and refused with a clear error past it; a get then costs what the
stored tree costs. Sizes are counted as the serialised value would be: the bytes of each string
or binary, 8 per number, boolean or container entry, and ``DICT_BYTES`` more per dictionary:
a dictionary costs CPython about that much however little it holds, and a parameter name
``/a/b/c/...`` makes one per level (its namespaces), so counting them is what bounds the
memory of a deep name.
"""

from __future__ import annotations

import copy
from collections.abc import Mapping
from typing import Any

from robomodel.errors import RobomodelError

__all__ = [
    "DICT_BYTES",
    "MAX_DEPTH",
    "MAX_KEY_DEPTH",
    "MAX_TREE_BYTES",
    "MAX_VALUE_BYTES",
    "ParamBoundError",
    "copy_tree",
    "expand_bounded",
    "expand_measured",
    "tree_size",
]

MAX_VALUE_BYTES = 32 * 1024 * 1024  # one value (a robot_description is well under 2 MiB)
MAX_TREE_BYTES = 256 * 1024 * 1024  # the whole server
MAX_DEPTH = 100  # nesting of dicts and lists
MAX_KEY_DEPTH = 100  # namespaces in a parameter's name (/a/b/c: 3)
DICT_BYTES = 240  # what CPython's smallest dictionaries cost (sys.getsizeof + GC header)


class ParamBoundError(RobomodelError):
    """A parameter value over the size or nesting bound."""


def _too_large(what: str, limit: int) -> str:
    return (
        f"{what} is larger than {limit / 2**20:.0f} MiB once expanded (YAML aliases repeating "
        "a block?); parameters are bounded to keep the server's memory bounded"
    )


def _leaf_size(value: Any) -> int:
    if isinstance(value, str):
        return len(value)  # characters: a close bound of the UTF-8 bytes for the sizes here
    if isinstance(value, bytes | bytearray):
        return len(value)
    data = getattr(value, "data", None)  # launch's Binary
    return len(data) if isinstance(data, bytes | bytearray) else 8


def _copy(value: Any) -> Any:
    """A plain tree: shared blocks copied apart, keys as strings, tuples as lists."""
    if isinstance(value, Mapping):
        return {str(key): _copy(item) for key, item in value.items()}
    if isinstance(value, list | tuple):
        return [_copy(item) for item in value]
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
        size = DICT_BYTES + sum(
            8 + len(str(k)) + _measure(v, memo, open_ids, depth + 1, what) for k, v in value.items()
        )
    else:
        size = 8 + sum(_measure(v, memo, open_ids, depth + 1, what) for v in value)
    open_ids.discard(key)
    memo[key] = size
    return size


def expand_measured(
    value: Any, *, what: str = "the value", limit: int = MAX_VALUE_BYTES
) -> tuple[Any, int]:
    """A plain tree copy of ``value`` (shared references copied apart) and its size, or
    ParamBoundError.

    The expanded size (and the nesting) is measured first, each shared block once, so an
    alias bomb is refused in the time it takes to read it, not to expand it; only a value
    within the bounds is copied. Dict keys become strings, tuples lists, as XML-RPC and YAML
    give them.
    """
    try:
        size = _measure(value, {}, set(), 0, what)
    except RecursionError:
        raise ParamBoundError(f"{what} is nested too deeply") from None
    if size > limit:
        raise ParamBoundError(_too_large(what, limit))
    return _copy(value), size


def expand_bounded(value: Any, *, what: str = "the value", limit: int = MAX_VALUE_BYTES) -> Any:
    """The plain tree of :func:`expand_measured`, without its size."""
    return expand_measured(value, what=what, limit=limit)[0]


def tree_size(value: Any) -> int:
    """The size of a plain tree (as :func:`expand_bounded` counts it). A loop, not a
    recursion: no tree is too deep for it."""
    size, stack = 0, [value]
    while stack:
        item = stack.pop()
        if isinstance(item, dict):
            size += DICT_BYTES + sum(8 + len(k) for k in item)
            stack.extend(item.values())
        elif isinstance(item, list):
            size += 8
            stack.extend(item)
        else:
            size += _leaf_size(item)
    return size


def _copy_leaf(value: Any) -> Any:
    if isinstance(value, str | bytes | int | float | None):
        return value  # immutable
    return copy.deepcopy(value)  # a bytearray, a Binary: flat


def copy_tree(value: Any) -> Any:
    """A copy of a plain tree, as ``copy.deepcopy`` makes it but by a loop, not a recursion."""
    if not isinstance(value, dict | list):
        return _copy_leaf(value)
    root: Any = {} if isinstance(value, dict) else []
    stack: list[tuple[Any, Any]] = [(value, root)]
    while stack:
        source, target = stack.pop()
        items = source.items() if isinstance(source, dict) else enumerate(source)
        for key, item in items:
            child = (
                {} if isinstance(item, dict) else [] if isinstance(item, list) else _copy_leaf(item)
            )
            if isinstance(target, dict):
                target[key] = child
            else:
                target.append(child)
            if isinstance(item, dict | list):
                stack.append((item, child))
    return root
