"""Evaluation of attribute and text values: ``${...}``, ``$(...)`` and the global names.

``eval_text`` mirrors the reference's ``eval_text`` (L700): a value made of a single
``${...}``/``$(...)`` keeps its Python type, otherwise the pieces are ``str()``-joined.
"""

from __future__ import annotations

import functools
import keyword
import math
import os
import re
from collections.abc import Callable
from types import CodeType

from robomodel._files import UserFileError, read_user_text
from robomodel.errors import InputError, Severity, close_matches
from robomodel.xacro._context import Context
from robomodel.xacro._lexer import LexError, Token, TokenKind, tokenize_text
from robomodel.xacro._safe_eval import (
    ExpressionError,
    UnsafeExpressionError,
    compile_expression,
    evaluate,
)
from robomodel.xacro._symbols import CircularDefinitionError, ReadOnlyNamespace, Scope
from robomodel.xacro._yaml import YamlDictWrapper, load_yaml_text
from robomodel.xacro.substitution_args import (
    XACRO,
    Lookup,
    SubstitutionError,
    SubstitutionScope,
    resolve_args,
)

TYPE_CHECKING = False  # typing.TYPE_CHECKING without importing typing (start-up)
if TYPE_CHECKING:
    from typing import Any

__all__ = ["abs_filename_spec", "build_globals", "eval_expression", "eval_text"]

_DIRECT = ("list", "dict", "map", "len", "str", "float", "int", "bool", "min", "max", "round")
_PYTHON = (
    *_DIRECT,
    *("abs", "all", "any", "complex", "divmod", "enumerate", "filter", "frozenset", "hash"),
    *("isinstance", "issubclass", "ord", "repr", "reversed", "slice", "set", "sum", "tuple"),
    *("zip", "sorted"),
)
_BUILTINS: dict[str, Any] = {
    name: __builtins__[name] if isinstance(__builtins__, dict) else getattr(__builtins__, name)
    for name in _PYTHON
}


@functools.lru_cache(maxsize=16384)
def _tokens(text: str) -> tuple[Token, ...]:
    return tokenize_text(text)


def abs_filename_spec(ctx: Context, spec: str) -> str:
    """Make ``spec`` relative to the directory of the current file (reference L69)."""
    if os.path.isabs(spec):
        return spec
    parent = ctx.current_file
    return os.path.join(os.path.dirname(parent) if parent else ".", spec)


def _undefined(ctx: Context, name: str, scope: Scope, expr: str) -> InputError:
    hint = close_matches(name, scope.names())
    suggestion = f"; did you mean {', '.join(repr(h) for h in hint)}?" if hint else ""
    return ctx.error(
        f"undefined name '{name}' in expression '${{{expr}}}'{suggestion}", needle="${" + expr
    )


@functools.lru_cache(maxsize=16384)
def _plan(expr: str) -> str | CodeType:
    """A bare name (looked up directly) or the checked, compiled code of ``expr``."""
    stripped = expr.strip()
    if stripped.isidentifier() and not keyword.iskeyword(stripped):
        return stripped
    return compile_expression(stripped)


def eval_expression(ctx: Context, expr: object, scope: Scope, source: str) -> object:
    """Evaluate the inside of one ``${...}`` (already substituted) in ``scope``."""
    if type(expr) is not str:
        raise ctx.error(f"expression '${{{source}}}' does not evaluate to text: {expr!r}")
    try:
        plan = _plan(expr)
        if type(plan) is str:
            try:
                return scope.lookup(plan)
            except KeyError:
                raise ExpressionError("undefined", name=plan) from None
        return evaluate(plan, scope.lookup, ctx.guards, ctx.base)  # type: ignore[arg-type]
    except InputError:
        raise
    except ExpressionError as exc:
        if exc.name is not None:
            raise _undefined(ctx, exc.name, scope, source) from None
        raise ctx.error(f"{exc} (in expression '${{{source}}}')", needle="${" + source) from None
    except CircularDefinitionError as exc:
        raise ctx.error(str(exc)) from None
    except Exception as exc:
        message = f"{type(exc).__name__}: {exc} (in expression '${{{source}}}')"
        raise ctx.error(message, needle="${" + source) from None


def _scope(ctx: Context) -> SubstitutionScope:
    """The run's substitution scope: ``$(eval)`` shares the run's work bounds and its
    bounded ``math``."""

    def evaluate_eval(expr: str, lookup: Lookup) -> object:
        code = compile_expression(expr.strip())
        return evaluate(code, lookup, ctx.guards, ctx.base)

    maths = ctx.globals.get("math")
    math_names = maths.as_dict() if isinstance(maths, ReadOnlyNamespace) else {}
    return SubstitutionScope(
        ctx.args,
        ctx.find_package,
        ctx.environ,
        filename=ctx.current_file,
        evaluate=evaluate_eval,
        math_names=math_names,
    )


def eval_extension(ctx: Context, text: str) -> str:
    """Resolve one ``$(...)`` group."""
    if text == "$(cwd)":
        return os.path.abspath(ctx.root_dir)
    try:
        return resolve_args(text, _scope(ctx), XACRO)
    except InputError:
        raise
    except SubstitutionError as exc:
        raise ctx.error(str(exc), needle=text[:-1]) from None
    except ExpressionError as exc:
        raise ctx.error(f"{exc} (in '{text}')") from None
    except Exception as exc:
        raise ctx.error(f"{type(exc).__name__}: {exc} (in '{text}')") from None


def eval_text(ctx: Context, text: str, scope: Scope) -> object:
    """Evaluate a value: typed when it is one ``${}``/``$()`` token, else a joined string."""
    if "$" not in text:
        return text
    try:
        tokens = _tokens(text)
    except LexError as exc:
        raise ctx.error(f"{exc}; write '$$' before '{{' or '(' for a literal '$'") from None
    ctx.charge_work(1)
    if len(tokens) == 1:
        kind, value = tokens[0]
        if kind is TokenKind.EXPR and "$" not in value:
            result = eval_expression(ctx, value, scope, value)
            if type(result) is str:
                ctx.charge_work(len(result) >> 6)
            return result
    results: list[object] = []
    for kind, value in tokens:
        if kind is TokenKind.TEXT:
            results.append(value)
        elif kind is TokenKind.EXPR:
            inner = eval_text(ctx, value, scope) if "$" in value else value
            results.append(eval_expression(ctx, inner, scope, value))
        else:
            results.append(eval_extension(ctx, f"$({eval_text(ctx, value, scope)})"))
    if len(results) == 1:
        return results[0]
    joined = "".join(map(str, results))
    ctx.charge_work(len(joined) >> 6)
    if len(joined) > ctx.limits.max_length:
        raise ctx.error(f"text longer than {ctx.limits.max_length} characters")
    return joined


def _tokenize(s: str, sep: str = ",; ", skip_empty: bool = True) -> list[str]:
    results = re.split(f"[{sep}]", s)
    return [item for item in results if item] if skip_empty else results


def _xacro_functions(ctx: Context) -> dict[str, object]:
    """The ``xacro.*`` namespace."""

    def load_yaml(filename: str) -> Any:
        path = abs_filename_spec(ctx, filename)
        from robomodel._yaml_bounded import YamlNestingError  # not at start-up: it loads typing

        ctx.filestack.append(path)
        try:
            text = read_user_text(path, what="YAML file")
            return load_yaml_text(text, functools.partial(_unit_value, ctx), where=str(path))
        except (UserFileError, YamlNestingError) as exc:
            raise ctx.error(f"load_yaml('{filename}'): {exc}") from None
        finally:
            ctx.filestack.pop()
            ctx.record_include(path)

    def report(severity: Severity, with_location: bool) -> Callable[..., str]:
        def emit(*args: object, **kwargs: object) -> str:
            ctx.warn(" ".join(map(str, args)), severity=severity)
            if kwargs.get("print_location", with_location):
                ctx.diagnostics.extend(ctx.notes())
            return ""

        return emit

    def fatal(*args: object) -> str:
        raise ctx.error(" ".join(map(str, args)))

    def arg(name: str) -> str:
        try:
            return ctx.args[name]
        except KeyError:
            raise ctx.error(f"undefined substitution argument '{name}'") from None

    return {
        "load_yaml": load_yaml,
        "abs_filename": lambda spec: abs_filename_spec(ctx, spec),
        "dotify": YamlDictWrapper,
        "arg": arg,
        "message": report(Severity.NOTE, False),
        "warning": report(Severity.WARNING, True),
        "error": report(Severity.ERROR, True),
        "print_location": report(Severity.NOTE, True),
        "fatal": fatal,
        "tokenize": _tokenize,
    }


def _unit_value(ctx: Context, value: str) -> object:
    try:
        code = compile_expression(value.strip())
        return evaluate(code, ctx.globals.__getitem__, ctx.guards, ctx.base)
    except ExpressionError as exc:
        raise ctx.error(f"invalid expression in YAML unit value '{value}': {exc}") from None


def _bounded_math(ctx: Context) -> dict[str, object]:
    names: dict[str, object] = {k: v for k, v in vars(math).items() if not k.startswith("_")}
    limit = 10_000

    def bounded(func: Callable[..., Any]) -> Callable[..., Any]:
        def call(*args: Any) -> Any:
            if any(isinstance(a, int) and a > limit for a in args):
                raise ExpressionError(f"math.{func.__name__}() argument larger than {limit}")
            return func(*args)

        return call

    for name in ("factorial", "comb", "perm"):
        names[name] = bounded(names[name])  # type: ignore[arg-type]
    return names


def _deprecated(ctx: Context, name: str, ns: str, func: Callable[..., Any]) -> Callable[..., Any]:
    def call(*args: Any, **kwargs: Any) -> Any:
        ctx.warn(f"Using {name}() directly is deprecated. Use {ns}.{name}() instead.")
        return func(*args, **kwargs)

    return call


def build_globals(ctx: Context) -> dict[str, object]:
    """The global symbols of one run (reference ``create_global_symbols``, L166)."""
    python: dict[str, object] = dict(_BUILTINS)
    python.update(
        {
            "True": True,
            "False": False,
            "range": ctx.guards.bounded_range,
            "type": _safe_type,
            "vars": _safe_vars,
        }
    )
    result: dict[str, object] = {name: python[name] for name in _DIRECT}
    result["True"] = True
    result["False"] = False
    for name in ("sorted", "range"):
        result[name] = _deprecated(ctx, name, "python", python[name])  # type: ignore[arg-type]
    result["python"] = ReadOnlyNamespace("python", python)
    maths = _bounded_math(ctx)
    result["math"] = ReadOnlyNamespace("math", maths)
    result.update(maths)
    xacro = _xacro_functions(ctx)
    for name in ("load_yaml", "abs_filename", "dotify"):
        result[name] = _deprecated(ctx, name, "xacro", xacro[name])  # type: ignore[arg-type]
    result["xacro"] = ReadOnlyNamespace("xacro", xacro)
    return result


def _safe_type(obj: object) -> type:
    """``type(obj)``; the metaclass (which builds new classes) is not handed out."""
    result = type(obj)
    if issubclass(result, type):
        raise UnsafeExpressionError("python.type() of a type is not allowed")
    return result


def _safe_vars(obj: object) -> dict[str, object]:
    if isinstance(obj, ReadOnlyNamespace):
        return obj.as_dict()
    if isinstance(obj, Scope):
        return {k: obj.lookup(k) for k in obj.values if not k.startswith("*")}
    raise UnsafeExpressionError(
        f"python.vars() on a {type(obj).__name__} value is not allowed (only on namespaces)"
    )
