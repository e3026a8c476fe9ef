"""roslaunch substitution args: ``$(find)``, ``$(arg)``, ``$(env)``, ``$(optenv)``, ``$(anon)``,
``$(dirname)`` and ``$(eval)``, with roslaunch 1.16's rules (``roslaunch/substitution_args.py``).

The engine is xacro's (:mod:`robomodel.xacro.substitution_args`, which xacro vendors from
roslaunch), in its :data:`~robomodel.xacro.substitution_args.ROSLAUNCH` dialect: everything but
``find`` first, then ``find`` (so an arg may expand to a ``$(find pkg)``). This module adds
what a launch file has on top: anonymous names of the run, the launch bounds on a value's
length, and ``$(eval)`` in the safe evaluator with roslaunch's names (``arg()``, ``find()``,
``env()``, ``optenv()``, ``anon()``, ``dirname()``, bare arg names converted as
``type="auto"`` values, ``true``/``false`` and ``math``).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, MutableMapping
from dataclasses import dataclass, field

from robomodel.launch.bounds import value_too_long
from robomodel.launch.ros1.names import anonymous_name
from robomodel.xacro.substitution_args import (
    ROSLAUNCH,
    ArgNotSet,
    ExpressionError,
    Lookup,
    SubstitutionError,
    SubstitutionScope,
    resolve_args,
    safe_evaluator,
)

__all__ = ["ArgNotSet", "SubstitutionContext", "SubstitutionError", "resolve"]


@dataclass
class SubstitutionContext:
    """What substitution needs: args in scope, anon names of the run, the current file."""

    args: MutableMapping[str, str]
    find: Callable[[str], str]
    environ: Mapping[str, str]
    filename: str | None = None
    anons: dict[str, str] = field(default_factory=dict)

    def anon(self, name: str) -> str:
        """The run's anonymous name for ``name`` (the same one each time)."""
        if name not in self.anons:
            self.anons[name] = anonymous_name(name, len(self.anons) + 1)
        return self.anons[name]


_MATH: Mapping[str, object] = {k: v for k, v in vars(math).items() if not k.startswith("_")}
_EVALUATE = safe_evaluator()  # one set of work bounds for the launch's $(eval)s


def _scope(ctx: SubstitutionContext) -> SubstitutionScope:
    return SubstitutionScope(
        ctx.args,
        ctx.find,
        ctx.environ,
        filename=ctx.filename,
        anon=ctx.anon,
        evaluate=_evaluate,
        math_names=_MATH,
        length_problem=value_too_long,
    )


def _evaluate(expr: str, lookup: Lookup) -> object:
    if "__" in expr:
        raise SubstitutionError("$(eval ...) may not contain double underscore expressions")
    return _EVALUATE(expr, lookup)


def _resolve_eval(text: str, ctx: SubstitutionContext) -> str:
    expr = text[7:-1]
    try:
        result = resolve_args(text, _scope(ctx), ROSLAUNCH)
        problem = value_too_long(len(result))
        if problem is not None:
            raise SubstitutionError(f"$(eval ...): {problem}")
        return result
    except ExpressionError as exc:
        if exc.name is not None:
            raise ArgNotSet.of(exc.name, list(ctx.args), ROSLAUNCH) from None
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
        return _resolve_eval(text, ctx)
    try:
        return resolve_args(text, _scope(ctx), ROSLAUNCH)
    except SubstitutionError:
        raise
    except Exception as exc:  # a package lookup's own errors
        raise SubstitutionError(str(exc)) from None
