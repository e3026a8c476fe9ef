"""rqt_publisher's expressions, without Python's ``eval``: ``sin(i/rate*speed)*diff + offset``.

rqt_publisher (publisher.py ``_evaluate_expression``) runs ``eval`` with ``i`` (the message
counter) and everything in ``math``, ``random`` and ``time`` in scope. Here the expression is
parsed into Python's AST and interpreted by a small tree walker that knows only numbers, the
arithmetic, comparison and conditional operators, the names ``i``, ``rate`` [Hz], ``t`` (=
``i / rate``) [s], the user's variables and a whitelist of math functions; anything else
(attributes, subscripts, strings, lambdas, keyword arguments) is refused when it is compiled.
"""

from __future__ import annotations

import ast
import math
import operator
import random
from collections.abc import Callable, Mapping
from typing import Any

from robomodel.errors import RobomodelError, close_matches

__all__ = ["Expression", "ExpressionError", "parse_variables"]

_MAX_CHARS = 2000
_MAX_NODES = 400

FUNCTIONS: dict[str, Callable[..., float]] = {
    name: getattr(math, name)
    for name in (
        "sin", "cos", "tan", "asin", "acos", "atan", "atan2", "sinh", "cosh", "tanh", "exp",
        "log", "log10", "log2", "sqrt", "fabs", "floor", "ceil", "fmod", "hypot", "degrees",
        "radians", "copysign", "trunc",
    )
}  # fmt: skip
FUNCTIONS.update(
    abs=abs,
    min=min,
    max=max,
    round=round,
    pow=math.pow,
    random=random.random,
    uniform=random.uniform,
)
CONSTANTS = {"pi": math.pi, "e": math.e, "tau": math.tau}

_BINARY: dict[type[ast.operator], Callable[[float, float], float]] = {
    ast.Add: operator.add,
    ast.Sub: operator.sub,
    ast.Mult: operator.mul,
    ast.Div: operator.truediv,
    ast.FloorDiv: operator.floordiv,
    ast.Mod: operator.mod,
    ast.Pow: math.pow,
}
_COMPARE: dict[type[ast.cmpop], Callable[[float, float], bool]] = {
    ast.Lt: operator.lt,
    ast.LtE: operator.le,
    ast.Gt: operator.gt,
    ast.GtE: operator.ge,
    ast.Eq: operator.eq,
    ast.NotEq: operator.ne,
}


class ExpressionError(RobomodelError):
    """An expression that does not parse, uses something not allowed, or fails to evaluate."""


class Expression:
    """A compiled expression; :meth:`evaluate` gives a float for the given variable values.

    Args:
        text: The expression as typed.
        names: The variable names it may use (besides the math functions and constants).
    """

    def __init__(self, text: str, names: tuple[str, ...] = ("i", "rate", "t")) -> None:
        self.text = text
        self.names = names
        if len(text) > _MAX_CHARS:
            raise ExpressionError(f"expression longer than {_MAX_CHARS} characters")
        try:
            tree = ast.parse(text.strip(), mode="eval")
        except SyntaxError as exc:
            raise ExpressionError(f"'{text}': {exc.msg} at column {exc.offset}") from None
        nodes = list(ast.walk(tree))
        if len(nodes) > _MAX_NODES:
            raise ExpressionError(f"expression has more than {_MAX_NODES} parts")
        for node in nodes:
            self._check(node)
        self._body = tree.body

    def _check(self, node: ast.AST) -> None:
        allowed = (
            ast.Expression, ast.Constant, ast.Name, ast.Load, ast.BinOp, ast.UnaryOp,
            ast.UAdd, ast.USub, ast.Not, ast.Call, ast.Compare, ast.IfExp, ast.BoolOp,
            ast.And, ast.Or, *_BINARY, *_COMPARE,
        )  # fmt: skip
        if not isinstance(node, allowed):
            raise ExpressionError(f"'{type(node).__name__}' is not allowed in an expression")
        if isinstance(node, ast.Constant) and (
            isinstance(node.value, bool) or not isinstance(node.value, (int, float))
        ):
            raise ExpressionError(f"only numbers may appear as constants, not {node.value!r}")
        if isinstance(node, ast.Name) and node.id not in FUNCTIONS:
            known = (*self.names, *CONSTANTS)
            if node.id not in known:
                hint = close_matches(node.id, [*known, *FUNCTIONS])
                extra = f" (did you mean {', '.join(hint)}?)" if hint else ""
                raise ExpressionError(
                    f"unknown name '{node.id}'{extra}; variables are: {', '.join(known)}"
                )
        if isinstance(node, ast.Call):
            if not isinstance(node.func, ast.Name) or node.func.id not in FUNCTIONS:
                called = node.func.id if isinstance(node.func, ast.Name) else ""
                hint = close_matches(called, FUNCTIONS) if called else []
                extra = f" (did you mean {', '.join(hint)}?)" if hint else ""
                raise ExpressionError(
                    f"cannot call '{called or ast.unparse(node.func)}'{extra}; functions are: "
                    f"{', '.join(sorted(FUNCTIONS))}"
                )
            if node.keywords:
                raise ExpressionError("keyword arguments are not allowed in an expression")

    def evaluate(self, values: Mapping[str, float]) -> float:
        """The value for ``values`` of the variables (every name given at compile time)."""
        try:
            result = float(self._eval(self._body, values))
        except ExpressionError:
            raise
        except (ArithmeticError, ValueError, TypeError) as exc:
            raise ExpressionError(f"'{self.text}': {exc}") from None
        return result

    def _eval(self, node: ast.expr, values: Mapping[str, float]) -> Any:
        if isinstance(node, ast.Constant):
            return float(node.value)  # type: ignore[arg-type]  # checked at compile
        if isinstance(node, ast.Name):
            if node.id in values:
                return float(values[node.id])
            if node.id in CONSTANTS:
                return CONSTANTS[node.id]
            raise ExpressionError(f"'{self.text}': no value for '{node.id}'")
        if isinstance(node, ast.BinOp):
            left, right = self._eval(node.left, values), self._eval(node.right, values)
            return _BINARY[type(node.op)](left, right)
        if isinstance(node, ast.UnaryOp):
            operand = self._eval(node.operand, values)
            if isinstance(node.op, ast.Not):
                return float(not operand)
            return -operand if isinstance(node.op, ast.USub) else +operand
        if isinstance(node, ast.Compare):
            left = self._eval(node.left, values)
            for op, comparator in zip(node.ops, node.comparators, strict=True):
                right = self._eval(comparator, values)
                if not _COMPARE[type(op)](left, right):
                    return 0.0
                left = right
            return 1.0
        if isinstance(node, ast.BoolOp):
            result = 0.0
            for value_node in node.values:
                result = self._eval(value_node, values)
                if isinstance(node.op, ast.And) and not result:
                    return result
                if isinstance(node.op, ast.Or) and result:
                    return result
            return result
        if isinstance(node, ast.IfExp):
            test = self._eval(node.test, values)
            return self._eval(node.body if test else node.orelse, values)
        assert isinstance(node, ast.Call) and isinstance(node.func, ast.Name)
        args = [self._eval(a, values) for a in node.args]
        return FUNCTIONS[node.func.id](*args)


def parse_variables(text: str) -> dict[str, float]:
    """User variables: ``speed=1, diff=(pi - -pi)/2, offset=pi - diff`` (``,``, ``;`` or lines).

    Each value is an expression over the constants and the variables before it.
    """
    values: dict[str, float] = {}
    for item in (p for chunk in text.splitlines() for p in chunk.replace(";", ",").split(",")):
        if not item.strip():
            continue
        name, sep, expr = item.partition("=")
        name = name.strip()
        if not sep or not name.isidentifier() or name in FUNCTIONS or name in CONSTANTS:
            raise ExpressionError(f"'{item.strip()}': give a variable as name=value")
        values[name] = Expression(expr, tuple(values)).evaluate(values)
    return values
