"""``$(...)`` substitution args: arg, find, env, optenv, eval, dirname, cwd.

A port of the vendored roslaunch code (xacro/substitution_args.py): the same splitting state
machine and the same two passes (``find`` last, so that ``$(arg x)`` may expand to a
``$(find pkg)``). Fixed here: ``$(dirname)`` returns the directory of the current file
(broken in the reference), and errors are reported once with the valid alternatives.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Mapping
from dataclasses import dataclass

from robomodel.errors import close_matches

__all__ = ["SubstitutionError", "SubstitutionHooks", "collect_args", "convert_auto", "resolve_args"]

_VALID = ("find", "env", "optenv", "dirname", "arg")


class SubstitutionError(Exception):
    """A ``$(...)`` could not be resolved."""


@dataclass(frozen=True, slots=True)
class SubstitutionHooks:
    """What substitution needs from the processing run.

    Attributes:
        args: The ``xacro:arg`` values and ``name:=value`` mappings.
        find: Returns a package's directory.
        current_file: The file being processed (None for string input).
        environ: The environment for ``env``/``optenv``.
        evaluate: Evaluates a ``$(eval ...)`` expression with a name lookup.
        math_names: The ``math`` names available in ``$(eval ...)`` (bounded versions).
    """

    args: Mapping[str, str]
    find: Callable[[str], str]
    current_file: str | None
    environ: Mapping[str, str]
    evaluate: Callable[[str, Callable[[str], object]], object]
    math_names: Mapping[str, object]


def collect_args(arg_str: str) -> list[str]:
    """Return the contents of the ``$(...)`` groups in ``arg_str`` (roslaunch's state machine)."""
    out, dollar, lp, inside = 0, 1, 2, 3
    buff: list[str] = []
    args: list[str] = []
    state = out
    for c in arg_str:
        if c == "$":
            if state == out:
                state = dollar
            elif state != dollar:
                raise SubstitutionError(
                    f'dollar signs "$" cannot be inside of substitution args [{arg_str}]'
                )
        elif c == "(":
            if state == dollar:
                state = lp
            elif state != out:
                raise SubstitutionError(
                    f'invalid left parenthesis "(" in substitution args [{arg_str}]'
                )
        elif c == ")":
            if state == inside:
                args.append("".join(buff))
                buff.clear()
            state = out
        elif state == dollar:
            state = out
        elif state == lp:
            state = inside
        if state == inside:
            buff.append(c)
    return args


def convert_auto(value: str) -> object:
    """roslaunch's ``convert_value(value, 'auto')``: float if it has a dot, int, bool, str."""
    try:
        return float(value) if "." in value else int(value)
    except ValueError:
        pass
    if value.lower() in ("true", "false"):
        return value.lower().strip() == "true"
    return value


def _arg_value(name: str, hooks: SubstitutionHooks) -> str:
    try:
        return hooks.args[name]
    except KeyError:
        hint = close_matches(name, hooks.args)
        known = ", ".join(sorted(hooks.args)) or "none"
        suggestion = f"; did you mean {', '.join(repr(h) for h in hint)}?" if hint else ""
        raise SubstitutionError(
            f"undefined substitution argument '{name}'{suggestion} (defined args: {known}); "
            f'declare it with <xacro:arg name="{name}" default="..."/> before its first use '
            f"or pass {name}:=VALUE"
        ) from None


def _dirname(hooks: SubstitutionHooks) -> str:
    if not hooks.current_file:
        raise SubstitutionError("cannot substitute $(dirname): the input is not a file")
    return os.path.abspath(os.path.dirname(hooks.current_file))


def _command(command: str, args: list[str], a: str, hooks: SubstitutionHooks) -> str:
    if command == "arg":
        if len(args) != 1:
            raise SubstitutionError(f"$(arg var) takes exactly one name [{a}]")
        return _arg_value(args[0], hooks)
    if command == "find":
        if len(args) != 1:
            raise SubstitutionError(f"$(find pkg) accepts exactly one argument [{a}]")
        return hooks.find(args[0])
    if command == "env":
        if len(args) != 1:
            raise SubstitutionError(f"$(env var) command only accepts one argument [{a}]")
        try:
            return hooks.environ[args[0]]
        except KeyError:
            raise SubstitutionError(
                f"environment variable '{args[0]}' is not set; use $(optenv {args[0]} "
                "default) for an optional one"
            ) from None
    if command == "optenv":
        if not args:
            raise SubstitutionError(f"$(optenv var) must specify an environment variable [{a}]")
        return hooks.environ.get(args[0], " ".join(args[1:]))
    return _dirname(hooks)


def _resolve_pass(arg_str: str, hooks: SubstitutionHooks, commands: tuple[str, ...]) -> str:
    resolved = arg_str
    for a in collect_args(arg_str):
        splits = [s for s in a.split(" ") if s]
        if not splits or splits[0] not in _VALID:
            raise SubstitutionError(
                f"unknown substitution command [{a}]; valid commands are "
                "arg, find, env, optenv, dirname, eval and cwd"
            )
        if splits[0] in commands:
            resolved = resolved.replace(f"$({a})", _command(splits[0], splits[1:], a, hooks))
    return resolved


def _eval_lookup(hooks: SubstitutionHooks) -> Callable[[str], object]:
    functions: dict[str, object] = {
        "arg": lambda name: convert_auto(_arg_value(name, hooks)),
        "dirname": lambda: _dirname(hooks),
        "env": lambda name: _command("env", [name], name, hooks),
        "optenv": lambda name, default="": hooks.environ.get(name, default),
        "find": hooks.find,
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
    functions.update(hooks.math_names)

    def lookup(name: str) -> object:
        if name in functions:
            return functions[name]
        return convert_auto(hooks.args[name])

    return lookup


def resolve_args(arg_str: str, hooks: SubstitutionHooks) -> str:
    """Resolve one ``$(...)`` group (and any others the text contains).

    Raises:
        SubstitutionError: unknown command, undefined arg, unset env variable, ...
    """
    if not arg_str:
        return arg_str
    if arg_str.startswith("$(eval ") and arg_str.endswith(")"):
        return str(hooks.evaluate(arg_str[7:-1], _eval_lookup(hooks)))
    resolved = _resolve_pass(arg_str, hooks, _VALID)
    return _resolve_pass(resolved, hooks, ("find",))
