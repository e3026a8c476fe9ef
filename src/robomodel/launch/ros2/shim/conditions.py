"""``launch.conditions``: whether an action is executed."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from robomodel.launch.ros2.shim.context import LaunchContext, SubstitutionFailure
from robomodel.launch.ros2.shim.substitutions import (
    normalize_to_list_of_substitutions,
    perform_substitutions,
)

__all__ = [
    "Condition",
    "IfCondition",
    "InvalidConditionExpressionError",
    "LaunchConfigurationEquals",
    "LaunchConfigurationNotEquals",
    "UnlessCondition",
    "evaluate_condition_expression",
]


class InvalidConditionExpressionError(SubstitutionFailure):
    """A condition's text is none of ``true``, ``false``, ``1``, ``0`` (any case)."""

    def __init__(self, expression: str, substitutions: Any, valid: list[str]) -> None:
        described = " + ".join(s.describe() for s in substitutions)
        super().__init__(
            f"Unexpected condition expression '{expression}' from '{described}', "
            f"expected one of: {valid}"
        )


def evaluate_condition_expression(context: LaunchContext, expression: Any) -> bool:
    """Strip, lower-case, then ``true``/``1`` -> True, ``false``/``0`` -> False, else error."""
    text = perform_substitutions(context, expression).strip().lower()
    if text in ("true", "1"):
        return True
    if text in ("false", "0"):
        return False
    raise InvalidConditionExpressionError(text, expression, ["true", "1", "false", "0"])


class Condition:
    """A predicate on the context, evaluated when the action it guards is visited."""

    def __init__(self, *, predicate: Callable[[LaunchContext], bool] | None = None) -> None:
        self._predicate = predicate

    def evaluate(self, context: LaunchContext) -> bool:
        """True if the guarded action runs."""
        return self._predicate(context) if self._predicate is not None else True

    def describe(self) -> str:
        """Text for introspection."""
        return self.__repr__()


class IfCondition(Condition):
    """Run the action when the expression is true."""

    def __init__(self, predicate_expression: Any) -> None:
        self._expression = normalize_to_list_of_substitutions(predicate_expression)
        super().__init__(predicate=self._evaluate)

    def _evaluate(self, context: LaunchContext) -> bool:
        return evaluate_condition_expression(context, self._expression)


class UnlessCondition(IfCondition):
    """Run the action when the expression is false."""

    def _evaluate(self, context: LaunchContext) -> bool:
        return not evaluate_condition_expression(context, self._expression)


class LaunchConfigurationEquals(Condition):
    """Run the action when a launch configuration equals a value (None: unset).

    Deprecated upstream in favour of ``IfCondition(EqualsSubstitution(...))``, still used.
    """

    def __init__(self, launch_configuration_name: str, expected_value: Any) -> None:
        self._name = launch_configuration_name
        self._expected = (
            None if expected_value is None else normalize_to_list_of_substitutions(expected_value)
        )
        super().__init__(predicate=self._evaluate)

    def _evaluate(self, context: LaunchContext) -> bool:
        expected = (
            None if self._expected is None else perform_substitutions(context, self._expected)
        )
        value = context.launch_configurations.get(self._name)
        return bool(value == expected)


class LaunchConfigurationNotEquals(LaunchConfigurationEquals):
    """Run the action when a launch configuration differs from a value."""

    def _evaluate(self, context: LaunchContext) -> bool:
        return not super()._evaluate(context)
