"""roslaunch substitution args: ``$(find)``, ``$(arg)``, ``$(env)``, ``$(optenv)``, ``$(anon)``,
``$(dirname)`` and ``$(eval)``, with roslaunch 1.16's rules (``roslaunch/substitution_args.py``).

The same two passes as roslaunch: everything but ``find`` first, then ``find`` (so an arg may
expand to a ``$(find pkg)``). ``$(eval)`` must be the whole value and runs in robomodel's safe
evaluator (the one xacro uses: no ``__`` names, no attribute escapes, bounded work), with
roslaunch's names: ``arg()``, ``find()``, ``env()``, ``optenv()``, ``anon()``, ``dirname()``,
bare arg names (converted as ``type="auto"`` values), ``true``/``false`` and ``math``.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, MutableMapping
from dataclasses import dataclass, field
from typing import Any

from robomodel.errors import close_matches
from robomodel.launch.bounds import value_too_long
from robomodel.launch.ros1.names import anonymous_name
from robomodel.xacro._safe_eval import (
    ExpressionError,
    Guards,
    Limits,
    compile_expression,
    evaluate,
)
from robomodel.xacro._subst import collect_args, convert_auto

__all__ = ["ArgNotSet", "SubstitutionContext", "SubstitutionError", "resolve"]

_VALID = ("find", "env", "optenv", "dirname", "anon", "arg")


class SubstitutionError(Exception):
    """A ``$(...)`` that cannot be resolved (roslaunch's SubstitutionException)."""


class ArgNotSet(SubstitutionError):
    """``$(arg name)`` of an arg with no value (roslaunch's ArgException)."""

    def __init__(self, name: str, known: list[str]) -> None:
        self.name = name
        self.location: Any = None  # the element that used it (SourceLocation), once known
        hint = close_matches(name, known)
        suggestion = f"; did you mean {', '.join(repr(h) for h in hint)}?" if hint else ""
        super().__init__(
            f"arg '{name}' is not set{suggestion} (set args: {', '.join(sorted(known)) or 'none'})"
        )


@dataclass
class SubstitutionContext:
    """What substitution needs: args in scope, anon names of the run, the current file."""

    args: MutableMapping[str, str]
    find: Callable[[str], str]
    environ: Mapping[str, str]
    filename: str | None = None
    anons: dict[str, str] = field(default_factory=dict)


def _arg(name: str, ctx: SubstitutionContext) -> str:
    try:
        return ctx.args[name]
    except KeyError:
        raise ArgNotSet(name, list(ctx.args)) from None


def _anon(name: str, ctx: SubstitutionContext) -> str:
    if name not in ctx.anons:
        ctx.anons[name] = anonymous_name(name, len(ctx.anons) + 1)
    return ctx.anons[name]


def _dirname(ctx: SubstitutionContext) -> str:
    import os

    if not ctx.filename:
        raise SubstitutionError(
            "Cannot substitute $(dirname), no file/directory information available."
        )
    return os.path.abspath(os.path.dirname(ctx.filename))


def _env(name: str, ctx: SubstitutionContext) -> str:
    try:
        return ctx.environ[name]
    except KeyError:
        raise SubstitutionError(
            f"environment variable '{name}' is not set; $(optenv {name} default) gives a default"
        ) from None


def _command(command: str, args: list[str], a: str, ctx: SubstitutionContext) -> str:
    if command == "arg":
        if len(args) != 1:
            raise SubstitutionError(f"$(arg var) must specify exactly one variable name [{a}]")
        return _arg(args[0], ctx)
    if command == "find":
        if len(args) != 1:
            raise SubstitutionError(f"$(find pkg) command only accepts one argument [{a}]")
        return ctx.find(args[0])
    if command == "env":
        if len(args) != 1:
            raise SubstitutionError(f"$(env var) command only accepts one argument [{a}]")
        return _env(args[0], ctx)
    if command == "optenv":
        if not args:
            raise SubstitutionError(f"$(optenv var) must specify an environment variable [{a}]")
        return ctx.environ.get(args[0], " ".join(args[1:]))
    if command == "anon":
        if len(args) != 1:
            raise SubstitutionError(f"$(anon var) must specify exactly one name [{a}]")
        return _anon(args[0], ctx)
    return _dirname(ctx)


def _pass(text: str, ctx: SubstitutionContext, commands: tuple[str, ...]) -> str:
    resolved = text
    for a in collect_args(text):
        splits = [s for s in a.split(" ") if s]
        if not splits or splits[0] not in _VALID:
            raise SubstitutionError(
                f"Unknown substitution command [{a}]. Valid commands are {list(_VALID)}"
            )
        if splits[0] in commands:
            value = _command(splits[0], splits[1:], a, ctx)
            count = 1 if splits[0] == "find" else resolved.count(f"$({a})")
            problem = value_too_long(len(resolved) + count * (len(value) - len(a) - 3))
            if problem is not None:
                raise SubstitutionError(f"$({a}): {problem}")
            resolved = resolved.replace(f"$({a})", value, count)
    return resolved


_GUARDS = Guards(Limits())


def _evaluate(expr: str, ctx: SubstitutionContext) -> str:
    if "__" in expr:
        raise SubstitutionError("$(eval ...) may not contain double underscore expressions")
    functions: dict[str, object] = {
        "arg": lambda name: convert_auto(_arg(name, ctx)),
        "anon": lambda name: _anon(name, ctx),
        "dirname": lambda: _dirname(ctx),
        "env": lambda name: _env(name, ctx),
        "optenv": lambda name, default="": ctx.environ.get(name, default),
        "find": ctx.find,
        "true": True,
        "false": False,
        "True": True,
        "False": False,
        "list": list,
        "dict": dict,
        "map": map,
        "str": str,
        "float": float,
        "int": int,
    }
    functions.update({k: v for k, v in vars(math).items() if not k.startswith("_")})

    def lookup(name: str) -> object:
        if name in functions:
            return functions[name]
        return convert_auto(ctx.args[name])

    try:
        code = compile_expression(expr.strip())
        result = str(evaluate(code, lookup, _GUARDS, _GUARDS.functions()))
        problem = value_too_long(len(result))
        if problem is not None:
            raise SubstitutionError(f"$(eval ...): {problem}")
        return result
    except ExpressionError as exc:
        if exc.name is not None:
            raise ArgNotSet(exc.name, list(ctx.args)) from None
        raise SubstitutionError(f"$(eval {expr}): {exc}") from None
    except SubstitutionError:
        raise
    except Exception as exc:
        raise SubstitutionError(f"$(eval {expr}): {type(exc).__name__}: {exc}") from None


def resolve(text: str | None, ctx: SubstitutionContext) -> str | None:
    """Resolve every ``$(...)`` in ``text`` (None stays None), as roslaunch's resolve_args."""
    if not text or "$" not in text:
        return text
    if text.startswith("$(eval ") and text.endswith(")"):
        return _evaluate(text[7:-1], ctx)
    try:
        resolved = _pass(text, ctx, ("env", "optenv", "dirname", "anon", "arg"))
        return _pass(resolved, ctx, ("find",))
    except SubstitutionError:
        raise
    except Exception as exc:  # collect_args' own syntax errors
        raise SubstitutionError(str(exc)) from None
