"""The safe evaluator for ``${...}`` expressions: an AST whitelist plus run-time guards.

The reference evaluates expressions with ``eval`` and empty builtins after checking only the
top-level code object's names for ``__`` (xacro/__init__.py L239), which a lambda or a
comprehension escapes. Here every expression is parsed, every node is checked against a
whitelist (names and attributes starting with ``_`` are refused at any depth, except the bare
throw-away name ``_``), and the tree is rewritten so that:

* attribute access goes through :meth:`Guards.attr`, which allows it only on data values
  (str, numbers, list, tuple, dict, set, YAML wrappers) and namespaces, and refuses
  ``str.format`` field names that reach attributes;
* ``**``, ``*``, ``+``, ``%`` and ``<<`` check the size of their result before computing it;
* every comprehension loop counts against an iteration budget.

Compiled code is cached by expression text, so each expression is checked once.
"""

from __future__ import annotations

import ast
import functools
import math
import re
import string
from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass
from types import CodeType

from robomodel.xacro._symbols import ReadOnlyNamespace, Scope

TYPE_CHECKING = False  # typing.TYPE_CHECKING without importing typing (start-up)
if TYPE_CHECKING:
    from typing import Any

__all__ = [
    "ExpressionError",
    "Guards",
    "Limits",
    "UnsafeExpressionError",
    "compile_expression",
    "evaluate",
]


class ExpressionError(Exception):
    """An expression could not be evaluated (syntax, undefined name, bound exceeded, ...)."""

    def __init__(self, message: str, *, name: str | None = None) -> None:
        super().__init__(message)
        self.name = name


class UnsafeExpressionError(ExpressionError):
    """An expression uses a construct the safe evaluator refuses."""


@dataclass(frozen=True, slots=True)
class Limits:
    """Bounds that turn runaway inputs into clear errors instead of hangs or MemoryError.

    Attributes:
        max_int_bits: Largest integer result of ``**``, ``*`` or ``<<``, in bits.
        max_length: Longest str/list/tuple an operator or ``range`` may create.
        max_iterations: Comprehension iterations allowed in one expression.
        max_macro_depth: Deepest nesting of macro calls and includes.
        max_nodes: Nodes that macro expansions and block insertions may create in one run.
        max_output_chars: Longest output document.
        max_work: Total expansion work of one run, in units: one per macro call, include and
            evaluated ``${}``/``$()`` value, one per node a macro, block or include creates, one
            per 64 characters of evaluated text. An exponential fan-out (a macro calling itself
            twice per level) or a property doubling its length per step is refused when it
            reaches this, well under a second; the real PR2 uses under 2 % of it.
    """

    max_int_bits: int = 65536
    max_length: int = 10_000_000
    max_iterations: int = 1_000_000
    max_macro_depth: int = 150
    max_nodes: int = 5_000_000
    max_output_chars: int = 256 * 1024 * 1024
    max_work: int = 600_000


_ALLOWED_NODES: tuple[type[ast.AST], ...] = (
    ast.Expression, ast.Constant, ast.Name, ast.Load, ast.Store, ast.Attribute, ast.Subscript,
    ast.Slice, ast.BinOp, ast.UnaryOp, ast.BoolOp, ast.Compare, ast.IfExp, ast.Call,
    ast.keyword, ast.Lambda, ast.arguments, ast.arg, ast.List, ast.Tuple, ast.Dict, ast.Set,
    ast.ListComp, ast.SetComp, ast.DictComp, ast.GeneratorExp, ast.comprehension, ast.Starred,
    ast.JoinedStr, ast.FormattedValue,
    ast.Add, ast.Sub, ast.Mult, ast.Div, ast.FloorDiv, ast.Mod, ast.Pow, ast.LShift,
    ast.RShift, ast.BitOr, ast.BitXor, ast.BitAnd, ast.UAdd, ast.USub, ast.Not, ast.Invert,
    ast.And, ast.Or, ast.Eq, ast.NotEq, ast.Lt, ast.LtE, ast.Gt, ast.GtE, ast.Is, ast.IsNot,
    ast.In, ast.NotIn,
)  # fmt: skip

_WIDTH = re.compile(r"\d{7,}")


def _private(name: str | None) -> bool:
    return name is not None and name.startswith("_") and name != "_"


def _refuse(what: str) -> UnsafeExpressionError:
    return UnsafeExpressionError(f"{what} is not allowed in xacro expressions")


def _check(tree: ast.AST) -> None:
    """Raise :class:`UnsafeExpressionError` for anything outside the whitelist."""
    for node in ast.walk(tree):
        if not isinstance(node, _ALLOWED_NODES):
            raise _refuse(f"'{type(node).__name__}' syntax")
        if isinstance(node, ast.Name) and _private(node.id):
            raise _refuse(f"the name '{node.id}' (names starting with '_')")
        if isinstance(node, ast.Attribute):
            if node.attr.startswith("_"):
                raise _refuse(f"the attribute '.{node.attr}' (attributes starting with '_')")
            if not isinstance(node.ctx, ast.Load):
                raise _refuse("assigning to an attribute")
        if isinstance(node, ast.Subscript) and not isinstance(node.ctx, ast.Load):
            raise _refuse("assigning to a subscript")
        if isinstance(node, ast.arg) and _private(node.arg):
            raise _refuse(f"the parameter name '{node.arg}'")
        if isinstance(node, ast.keyword) and _private(node.arg):
            raise _refuse(f"the keyword '{node.arg}'")
        if isinstance(node, ast.Constant) and isinstance(node.value, str):
            continue
        if isinstance(node, ast.FormattedValue) and node.format_spec is not None:
            for part in ast.walk(node.format_spec):
                if isinstance(part, ast.Constant) and _WIDTH.search(str(part.value)):
                    raise ExpressionError("format width too large")


def _call(func: str, *args: ast.expr) -> ast.Call:
    return ast.Call(func=ast.Name(id=func, ctx=ast.Load()), args=list(args), keywords=[])


_BINOP_GUARDS: dict[type[ast.operator], str] = {
    ast.Pow: "_rm_pow",
    ast.Mult: "_rm_mul",
    ast.Add: "_rm_add",
    ast.Mod: "_rm_mod",
    ast.LShift: "_rm_lshift",
}


class _Rewriter(ast.NodeTransformer):
    """Route attribute access, size-changing operators and loops through the guards."""

    def visit_Attribute(self, node: ast.Attribute) -> ast.AST:
        value = self.visit(node.value)
        return ast.copy_location(_call("_rm_attr", value, ast.Constant(node.attr)), node)

    def visit_BinOp(self, node: ast.BinOp) -> ast.AST:
        self.generic_visit(node)
        guard = _BINOP_GUARDS.get(type(node.op))
        if guard is None:
            return node
        return ast.copy_location(_call(guard, node.left, node.right), node)

    def visit_comprehension(self, node: ast.comprehension) -> ast.AST:
        self.generic_visit(node)
        node.iter = _call("_rm_iter", node.iter)
        return node


@functools.lru_cache(maxsize=8192)
def compile_expression(expr: str) -> CodeType:
    """Parse, check and compile ``expr`` (already stripped).

    Raises:
        ExpressionError: syntax error or a refused construct.
    """
    try:
        tree = ast.parse(expr, "<expression>", mode="eval")
    except SyntaxError as exc:
        raise ExpressionError(f"invalid expression syntax: {exc.msg}") from None
    _check(tree)
    tree = ast.fix_missing_locations(_Rewriter().visit(tree))
    code: CodeType = compile(tree, "<expression>", "eval")
    return code


_DATA_TYPES = (str, int, float, complex, bool, list, tuple, dict, set, frozenset, range)
_TYPE_OBJECTS = frozenset(_DATA_TYPES)
_REFUSED_ATTRS = frozenset({"format_map", "mro"})
_SIZED_STR_METHODS = frozenset({"ljust", "rjust", "center", "zfill", "expandtabs"})


def _check_format(fmt: str, limits: Limits) -> None:
    for _literal, field, spec, _conversion in string.Formatter().parse(fmt):
        if field and ("." in field or field.startswith("_")):
            raise _refuse(f"the format field '{{{field}}}' (attribute access in str.format)")
        if spec:
            if _WIDTH.search(spec):
                raise ExpressionError("format width too large")
            _check_format(spec, limits)


class Guards:
    """The run-time checks the rewritten expressions call; one instance per processing run."""

    def __init__(self, limits: Limits) -> None:
        self.limits = limits
        self.remaining = limits.max_iterations

    def functions(self) -> dict[str, object]:
        """The guard functions by the names the rewriter uses."""
        return {
            "_rm_attr": self.attr,
            "_rm_pow": self.pow,
            "_rm_mul": self.mul,
            "_rm_add": self.add,
            "_rm_mod": self.mod,
            "_rm_lshift": self.lshift,
            "_rm_iter": self.iterate,
            "__builtins__": {},
        }

    def attr(self, obj: object, name: str) -> object:
        """``obj.name``, only for data values and namespaces."""
        if isinstance(obj, ReadOnlyNamespace):
            return obj.lookup(name)
        if isinstance(obj, Scope) and obj.namespace:
            try:
                return obj.lookup(name)
            except KeyError:
                raise NameError(f"name '{name}' is not defined") from None
        if isinstance(obj, _DATA_TYPES) or (type(obj) is type and obj in _TYPE_OBJECTS):
            if name in _REFUSED_ATTRS:
                raise _refuse(f"'.{name}'")
            if name == "format" and isinstance(obj, str):
                return self._format(obj)
            if name == "format":
                raise _refuse("'.format' on a type")
            value = getattr(obj, name)
            if isinstance(obj, str) and name in _SIZED_STR_METHODS:
                return self._sized(value)
            if isinstance(obj, str) and name in ("join", "replace"):
                return self._checked_result(obj, value)
            return value
        raise UnsafeExpressionError(
            f"attribute access '.{name}' on a {type(obj).__name__} value is not allowed; "
            "attributes are available on str, numbers, list, tuple, dict, set, YAML data "
            "and namespaces"
        )

    def _format(self, fmt: str) -> Callable[..., str]:
        _check_format(fmt, self.limits)
        return fmt.format

    def _sized(self, method: Callable[..., Any]) -> Callable[..., Any]:
        def call(*args: Any) -> Any:
            if args and isinstance(args[0], int) and args[0] > self.limits.max_length:
                raise ExpressionError(f"string longer than {self.limits.max_length} characters")
            return method(*args)

        return call

    def _checked_result(self, obj: str, method: Callable[..., Any]) -> Callable[..., Any]:
        limit = self.limits.max_length

        def call(*args: Any) -> Any:
            if method.__name__ == "join":
                items = list(args[0]) if args else []
                total = sum(len(i) for i in items if isinstance(i, str)) + len(obj) * len(items)
                if total > limit:
                    raise ExpressionError(f"string longer than {limit} characters")
                return method(items)
            if len(args) >= 2 and isinstance(args[1], str) and isinstance(args[0], str):
                count = obj.count(args[0]) if args[0] else len(obj) + 1
                if len(obj) + count * len(args[1]) > limit:
                    raise ExpressionError(f"string longer than {limit} characters")
            return method(*args)

        return call

    def _check_bits(self, bits: float) -> None:
        if bits > self.limits.max_int_bits:
            raise ExpressionError(
                f"integer result too large (more than {self.limits.max_int_bits} bits)"
            )

    def _check_length(self, length: int) -> None:
        if length > self.limits.max_length:
            raise ExpressionError(f"result longer than {self.limits.max_length} items")

    def pow(self, a: Any, b: Any) -> Any:
        """``a ** b`` with a bound on integer size."""
        if isinstance(a, int) and isinstance(b, int) and b > 0 and abs(a) > 1:
            self._check_bits(b * math.log2(abs(a)))
        return a**b

    def mul(self, a: Any, b: Any) -> Any:
        """``a * b`` with bounds on integer and sequence size."""
        if isinstance(a, int) and isinstance(b, int):
            self._check_bits(abs(a).bit_length() + abs(b).bit_length())
        elif isinstance(b, int) and isinstance(a, (str, list, tuple)):
            self._check_length(len(a) * b)
        elif isinstance(a, int) and isinstance(b, (str, list, tuple)):
            self._check_length(len(b) * a)
        return a * b

    def add(self, a: Any, b: Any) -> Any:
        """``a + b`` with a bound on sequence size."""
        if isinstance(a, (str, list, tuple)) and isinstance(b, (str, list, tuple)):
            self._check_length(len(a) + len(b))
        return a + b

    def mod(self, a: Any, b: Any) -> Any:
        """``a % b``; for printf-style formatting, refuse huge widths."""
        if isinstance(a, str):
            if _WIDTH.search(a):
                raise ExpressionError("format width too large")
            args = b if isinstance(b, tuple) else (b,)
            if "*" in a and any(isinstance(x, int) and x > self.limits.max_length for x in args):
                raise ExpressionError("format width too large")
            result = a % b
            self._check_length(len(result))
            return result
        return a % b

    def lshift(self, a: Any, b: Any) -> Any:
        """``a << b`` with a bound on integer size."""
        if isinstance(a, int) and isinstance(b, int) and a:
            self._check_bits(abs(a).bit_length() + b)
        return a << b

    def iterate(self, iterable: Iterable[Any]) -> Iterator[Any]:
        """Iterate a comprehension's source, counting against the iteration budget."""
        for item in iterable:
            self.remaining -= 1
            if self.remaining < 0:
                raise ExpressionError(
                    f"expression loops more than {self.limits.max_iterations} times"
                )
            yield item

    def bounded_range(self, *args: int) -> range:
        """``range`` that refuses more than ``max_length`` items."""
        result = range(*args)
        try:
            length = len(result)
        except OverflowError:
            length = self.limits.max_length + 1
        self._check_length(length)
        return result


class _Globals(dict[str, object]):
    """The globals mapping of one evaluation: names resolve through the symbol table."""

    __slots__ = ("lookup",)
    lookup: Callable[[str], object]

    def __missing__(self, key: str) -> object:
        # Not cached: a lambda keeps this mapping as its globals and, as in the reference,
        # must see a property's current value at every call.
        return self.lookup(key)


def evaluate(
    code: CodeType,
    lookup: Callable[[str], object],
    guards: Guards,
    base: dict[str, object],
) -> object:
    """Run compiled ``code`` with names resolved by ``lookup`` (raising ``KeyError``).

    Raises:
        ExpressionError: for undefined names (with ``.name`` set), exceeded bounds and
            refused run-time operations; other exceptions of the expression propagate.
    """
    namespace = _Globals(base)
    namespace.lookup = lookup
    guards.remaining = guards.limits.max_iterations
    try:
        return eval(code, namespace)
    except NameError as exc:
        name = getattr(exc, "name", None)
        raise ExpressionError(str(exc), name=name) from None
    except RecursionError:
        raise ExpressionError("expression recursion too deep") from None
    except MemoryError:
        raise ExpressionError("expression needs too much memory") from None
