"""Symbol tables with the reference's scoping and lazy evaluation (xacro ``Table``, L312).

A :class:`Scope` stores property values; strings stored lazily are evaluated at first access in
the scope that holds them. Lookups walk the parent chain and end in the global symbols.
:class:`Scope` with ``namespace=True`` is the reference's ``NameSpace`` (``<xacro:include ns=>``),
which also allows dotted access ``${ns.name}``.
"""

from __future__ import annotations

import keyword
import unicodedata
from collections.abc import Callable, Iterator, Mapping

__all__ = [
    "BooleanError",
    "CircularDefinitionError",
    "ReadOnlyNamespace",
    "Scope",
    "eval_literal",
    "is_valid_name",
    "to_boolean",
]


class CircularDefinitionError(Exception):
    """A lazily evaluated property refers to itself."""


class BooleanError(ValueError):
    """A condition value is not a boolean expression."""


def to_boolean(value: object, condition: object) -> bool:
    """Convert an evaluated condition as ``get_boolean_value`` does (L851).

    Strings ``true``/``True``/``false``/``False`` are accepted and any other string goes through
    ``bool(int(s))`` (so ``"1.0"`` is refused); other values use ``bool()``.
    """
    try:
        if isinstance(value, str):
            if value in ("true", "True"):
                return True
            if value in ("false", "False"):
                return False
            return bool(int(value))
        return bool(value)
    except Exception:
        raise BooleanError(
            f'Xacro conditional "{condition}" evaluated to "{value}", which is not a boolean '
            "expression; use true/false, 1/0 or a ${...} expression"
        ) from None


def eval_literal(value: object) -> object:
    """Type a stored value as ``Table._eval_literal`` does: quoted str, int, float, bool, str."""
    if not isinstance(value, str):
        return value
    if len(value) >= 2 and value[0] == "'" and value[-1] == "'":
        return value[1:-1]
    if "_" in value:
        return value
    try:
        return int(value)
    except ValueError:
        pass
    try:
        return float(value)
    except ValueError:
        pass
    if value in ("true", "True"):
        return True
    if value in ("false", "False"):
        return False
    return value


def is_valid_name(name: object) -> bool:
    """Whether ``name`` is a Python identifier usable as a property or macro name."""
    return (
        isinstance(name, str)
        and name.isidentifier()
        and not keyword.iskeyword(name)
        and unicodedata.normalize("NFKC", name) == name
    )


class ReadOnlyNamespace:
    """A fixed namespace of global names (``math``, ``python``, ``xacro``) with dotted access."""

    __slots__ = ("_items", "name")

    def __init__(self, name: str, items: Mapping[str, object]) -> None:
        self.name = name
        self._items = dict(items)

    def lookup(self, key: str) -> object:
        """Return the member ``key`` or raise ``NameError``."""
        try:
            return self._items[key]
        except KeyError:
            raise NameError(f"name '{key}' is not defined") from None

    def names(self) -> Iterator[str]:
        """The member names."""
        return iter(self._items)

    def as_dict(self) -> dict[str, object]:
        """A copy of the members."""
        return dict(self._items)


Resolver = Callable[[str, "Scope"], object]


class Scope:
    """One level of the symbol table (a macro body, a namespace, or the document's top level).

    Args:
        parent: The enclosing scope, or None for a top-level table.
        root: The global symbols, shared by every scope of one run (may be empty for macro
            tables, as in the reference).
        resolver: Evaluates a lazily stored string in a given scope.
        namespace: Whether this is a ``NameSpace`` created by ``<xacro:include ns=...>``.
    """

    __slots__ = ("namespace", "parent", "recursive", "resolver", "root", "unevaluated", "values")

    def __init__(
        self,
        parent: Scope | None,
        root: dict[str, object],
        resolver: Resolver | None = None,
        *,
        namespace: bool = False,
    ) -> None:
        self.parent = parent
        self.root = root
        self.resolver: Resolver | None = (
            resolver if resolver is not None or parent is None else parent.resolver
        )
        self.namespace = namespace
        self.values: dict[str, object] = {}
        self.unevaluated: set[str] = set()
        self.recursive: list[str] = []

    def _resolve(self, key: str) -> object:
        if key in self.unevaluated:
            if key in self.recursive:
                chain = " -> ".join([*self.recursive, key])
                raise CircularDefinitionError(
                    f"circular variable definition: {chain}; consider disabling lazy "
                    'evaluation via lazy_eval="false"'
                )
            self.recursive.append(key)
            try:
                if self.resolver is None:  # pragma: no cover - every value table has one
                    raise RuntimeError("no resolver for lazy values")
                self.values[key] = eval_literal(self.resolver(str(self.values[key]), self))
                self.unevaluated.discard(key)
            finally:
                self.recursive.remove(key)
        return self.values[key]

    def lookup(self, key: str) -> object:
        """Return the value of ``key`` visible from here, or raise ``KeyError``."""
        scope: Scope | None = self
        while scope is not None:
            values = scope.values
            if key in values:
                if key in scope.unevaluated:
                    return scope._resolve(key)
                return values[key]
            scope = scope.parent
        return self.root[key]

    def __contains__(self, key: object) -> bool:
        scope: Scope | None = self
        while scope is not None:
            if key in scope.values:
                return True
            scope = scope.parent
        return key in self.root

    def define(self, key: str, value: object, *, unevaluated: bool) -> bool:
        """Store ``value`` (typed by :func:`eval_literal`); return True if it shadows a global."""
        shadows = key in self.root
        value = eval_literal(value)
        self.values[key] = value
        if unevaluated and isinstance(value, str):
            self.unevaluated.add(key)
        else:
            self.unevaluated.discard(key)
        return shadows

    def delete(self, key: str) -> bool:
        """Remove ``key`` here and in every parent; return True if it is a global symbol."""
        scope: Scope | None = self
        while scope is not None:
            scope.values.pop(key, None)
            scope.unevaluated.discard(key)
            scope = scope.parent
        return key in self.root

    def top(self) -> Scope:
        """The outermost scope of this chain (the document's global property table)."""
        scope = self
        while scope.parent is not None:
            scope = scope.parent
        return scope

    def names(self) -> set[str]:
        """Every name visible from here (for "did you mean" hints)."""
        found: set[str] = set(self.root)
        scope: Scope | None = self
        while scope is not None:
            found.update(k for k in scope.values if not k.startswith("*"))
            scope = scope.parent
        return found
