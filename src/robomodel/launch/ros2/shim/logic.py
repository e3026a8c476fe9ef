"""Boolean and comparison substitutions (``$(not)``, ``$(and)``, ``$(equals)``, ``$(if)``...)."""

from __future__ import annotations

import math
from typing import Any

from robomodel.launch.ros2.shim.context import LaunchContext, SubstitutionFailure
from robomodel.launch.ros2.shim.substitutions import (
    Substitution,
    coerce_bool,
    normalize_to_list_of_substitutions,
    perform_substitutions,
)

__all__ = [
    "AllSubstitution",
    "AndSubstitution",
    "AnySubstitution",
    "EqualsSubstitution",
    "IfElseSubstitution",
    "NotEqualsSubstitution",
    "NotSubstitution",
    "OrSubstitution",
]


def _bool_of(context: LaunchContext, subs: list[Substitution], what: str) -> bool:
    text = perform_substitutions(context, subs)
    try:
        return coerce_bool(text)
    except SubstitutionFailure:
        raise SubstitutionFailure(f"{what}: invalid condition value '{text}'") from None


class NotSubstitution(Substitution):
    """``'true'`` if the value is false (``$(not x)``)."""

    def __init__(self, value: Any) -> None:
        self.value = normalize_to_list_of_substitutions(value)

    def describe(self) -> str:
        return f"NotSubstitution({self.value})"

    def perform(self, context: LaunchContext) -> str:
        return str(not _bool_of(context, self.value, "NotSubstitution")).lower()


class AndSubstitution(Substitution):
    """``'true'`` if both values are true (``$(and a b)``)."""

    def __init__(self, left: Any, right: Any) -> None:
        self.left = normalize_to_list_of_substitutions(left)
        self.right = normalize_to_list_of_substitutions(right)

    def describe(self) -> str:
        return f"AndSubstitution({self.left} {self.right})"

    def perform(self, context: LaunchContext) -> str:
        left = _bool_of(context, self.left, "AndSubstitution")
        return str(left and _bool_of(context, self.right, "AndSubstitution")).lower()


class OrSubstitution(AndSubstitution):
    """``'true'`` if either value is true (``$(or a b)``)."""

    def perform(self, context: LaunchContext) -> str:
        left = _bool_of(context, self.left, "OrSubstitution")
        return str(left or _bool_of(context, self.right, "OrSubstitution")).lower()


class AllSubstitution(Substitution):
    """``'true'`` if every value is true (``$(all ...)``)."""

    def __init__(self, *args: Any) -> None:
        self.args = [normalize_to_list_of_substitutions(a) for a in args]

    def describe(self) -> str:
        return f"AllSubstitution({' '.join(str(a) for a in self.args)})"

    def perform(self, context: LaunchContext) -> str:
        return str(all(_bool_of(context, a, "AllSubstitution") for a in self.args)).lower()


class AnySubstitution(AllSubstitution):
    """``'true'`` if some value is true (``$(any ...)``)."""

    def describe(self) -> str:
        return f"AnySubstitution({' '.join(str(a) for a in self.args)})"

    def perform(self, context: LaunchContext) -> str:
        return str(any(_bool_of(context, a, "AnySubstitution") for a in self.args)).lower()


def _is_bool_text(text: str) -> bool:
    return text.lower() in ("true", "false", "1", "0")


def _is_float_text(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


class EqualsSubstitution(Substitution):
    """``'true'`` if both sides are equal, comparing booleans and numbers as launch does."""

    def __init__(self, left: Any, right: Any) -> None:
        self.left = normalize_to_list_of_substitutions(
            ""
            if left is None
            else str(left)
            if not isinstance(left, (str, Substitution, list, tuple))
            else left
        )
        self.right = normalize_to_list_of_substitutions(
            ""
            if right is None
            else str(right)
            if not isinstance(right, (str, Substitution, list, tuple))
            else right
        )

    def describe(self) -> str:
        return f"EqualsSubstitution({self.left} {self.right})"

    def perform(self, context: LaunchContext) -> str:
        left = perform_substitutions(context, self.left)
        right = perform_substitutions(context, self.right)
        if _is_bool_text(left) and _is_bool_text(right):
            return str((left.lower() in ("true", "1")) == (right.lower() in ("true", "1"))).lower()
        if _is_float_text(left) and _is_float_text(right):
            return str(math.isclose(float(left), float(right))).lower()
        return str(left == right).lower()


class NotEqualsSubstitution(EqualsSubstitution):
    """The negation of :class:`EqualsSubstitution` (``$(not-equals a b)``)."""

    def describe(self) -> str:
        return f"NotEqualsSubstitution({self.left} {self.right})"

    def perform(self, context: LaunchContext) -> str:
        return str(super().perform(context) != "true").lower()


class IfElseSubstitution(Substitution):
    """``if_value`` when the condition is true, else ``else_value`` (``$(if c a b)``)."""

    def __init__(self, condition: Any, if_value: Any = "", else_value: Any = "") -> None:
        self.condition = normalize_to_list_of_substitutions(condition)
        self.if_value = normalize_to_list_of_substitutions(if_value)
        self.else_value = normalize_to_list_of_substitutions(else_value)

    def describe(self) -> str:
        return f"IfElseSubstitution({self.condition}, {self.if_value}, {self.else_value})"

    def perform(self, context: LaunchContext) -> str:
        chosen = (
            self.if_value
            if _bool_of(context, self.condition, "IfElseSubstitution")
            else self.else_value
        )
        return perform_substitutions(context, chosen)
