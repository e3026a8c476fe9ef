"""ROS's ``$(...)`` substitution args, one engine for xacro and ROS 1 launch files.

xacro 2.1.1 vendors roslaunch's ``substitution_args.py`` (``xacro/substitution_args.py``), so
both read ``$(...)`` with the same splitting state machine and the same two passes: everything
but ``find`` first, then ``find`` (an arg may expand to a ``$(find pkg)``). ``$(eval ...)`` must
be the whole value; it sees ``arg()``, ``find()``, ``env()``, ``optenv()``, ``dirname()`` (and
``anon()`` where ``$(anon)`` exists), bare arg names converted as ``type="auto"`` values,
``true``/``false`` and the ``math`` names. It runs in robomodel's safe evaluator (no ``__``
names, no attribute escapes, bounded work): :func:`safe_evaluator`.

What differs between the two is a :class:`Dialect`: the commands it knows (roslaunch 1.16 has
``$(anon)``; xacro has none), its messages, and its ``$(find)`` rules (robomodel's xacro also
resolves ``find`` in the first pass and replaces every copy of a group at once). What differs between runs is a :class:`SubstitutionScope`: the args, the
package lookup, the environment, the current file, ``$(eval)``'s evaluator.

Example:
    >>> from robomodel.xacro.substitution_args import XACRO, SubstitutionScope, resolve_args
    >>> scope = SubstitutionScope({"x": "1"}, find=str, environ={})
    >>> resolve_args("$(arg x)/$(optenv NO_SUCH_VARIABLE a b)", scope, XACRO)
    '1/a b'
"""

from __future__ import annotations

import os
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field

from robomodel.errors import SourceLocation, close_matches
from robomodel.xacro._safe_eval import ExpressionError, Guards, Limits, compile_expression, evaluate

__all__ = [
    "ROSLAUNCH",
    "XACRO",
    "ArgNotSet",
    "Dialect",
    "ExpressionError",
    "Lookup",
    "SubstitutionError",
    "SubstitutionScope",
    "collect_args",
    "convert_auto",
    "resolve_args",
    "safe_evaluator",
]

Lookup = Callable[[str], object]
"""A name lookup for ``$(eval ...)``: the value of a name (KeyError: undefined)."""


class SubstitutionError(Exception):
    """A ``$(...)`` that cannot be resolved (roslaunch's SubstitutionException)."""


class ArgNotSet(SubstitutionError):
    """``$(arg name)`` of an arg with no value (roslaunch's ArgException).

    Attributes:
        name: The arg.
        known: The args that are set.
        location: Where it was used (a SourceLocation), once the caller knows it.
    """

    def __init__(self, name: str, known: list[str], message: str) -> None:
        self.name = name
        self.known = known
        self.location: SourceLocation | None = None
        super().__init__(message)

    @classmethod
    def of(cls, name: str, known: list[str], dialect: Dialect) -> ArgNotSet:
        """The error for ``name`` in ``dialect``'s words, with the closest set args."""
        hint = close_matches(name, known)
        suggestion = f"; did you mean {', '.join(repr(h) for h in hint)}?" if hint else ""
        message = dialect.undefined_arg.format(
            name=name, suggestion=suggestion, known=", ".join(sorted(known)) or "none"
        )
        return cls(name, known, message)


@dataclass(frozen=True, slots=True)
class Dialect:
    """The commands and messages of one reader of ``$(...)``.

    The messages are ``str.format`` templates: ``{a}`` is the group's text (``arg a b``),
    ``{name}`` the arg or variable, ``{commands}`` the list of commands, ``{suggestion}``
    a "did you mean" part and ``{known}`` the args that are set.

    Attributes:
        commands: The commands it knows (``eval`` apart).
        find_first_only: ``$(find)`` replaces only the first copy of its group (roslaunch).
        find_in_first_pass: ``$(find)`` is resolved in the first pass too, as it comes
            (robomodel's xacro); else only in the second (roslaunch).
        unknown_command: A command it does not know.
        arg_count: ``$(arg)`` without exactly one name.
        find_count: ``$(find)`` without exactly one package.
        env_unset: ``$(env name)`` of an unset variable.
        no_dirname: ``$(dirname)`` with no current file.
        undefined_arg: ``$(arg name)`` of an arg that is not set.
    """

    commands: tuple[str, ...]
    find_first_only: bool
    find_in_first_pass: bool
    unknown_command: str
    arg_count: str
    find_count: str
    env_unset: str
    no_dirname: str
    undefined_arg: str


ROSLAUNCH = Dialect(
    commands=("find", "env", "optenv", "dirname", "anon", "arg"),
    find_first_only=True,
    find_in_first_pass=False,
    unknown_command="Unknown substitution command [{a}]. Valid commands are {commands}",
    arg_count="$(arg var) must specify exactly one variable name [{a}]",
    find_count="$(find pkg) command only accepts one argument [{a}]",
    env_unset=(
        "environment variable '{name}' is not set; $(optenv {name} default) gives a default"
    ),
    no_dirname="Cannot substitute $(dirname), no file/directory information available.",
    undefined_arg="arg '{name}' is not set{suggestion} (set args: {known})",
)
"""roslaunch 1.16's ``substitution_args.py`` (with robomodel's clearer unset-arg message)."""

XACRO = Dialect(
    commands=("find", "env", "optenv", "dirname", "arg"),
    find_first_only=False,
    find_in_first_pass=True,
    unknown_command=(
        "unknown substitution command [{a}]; valid commands are "
        "arg, find, env, optenv, dirname, eval and cwd"
    ),
    arg_count="$(arg var) takes exactly one name [{a}]",
    find_count="$(find pkg) accepts exactly one argument [{a}]",
    env_unset=(
        "environment variable '{name}' is not set; use $(optenv {name} default) for an optional one"
    ),
    no_dirname="cannot substitute $(dirname): the input is not a file",
    undefined_arg=(
        "undefined substitution argument '{name}'{suggestion} (defined args: {known}); "
        'declare it with <xacro:arg name="{name}" default="..."/> before its first use '
        "or pass {name}:=VALUE"
    ),
)
"""xacro 2.1.1's copy (``$(cwd)`` is the caller's: it is not a substitution arg there either).
Fixed here: ``$(dirname)`` is the current file's directory (broken in the reference)."""


@dataclass(frozen=True, slots=True)
class SubstitutionScope:
    """What one run gives substitution.

    Attributes:
        args: The args in scope (``<arg>`` values; ``xacro:arg`` values and mappings).
        find: Returns a package's directory.
        environ: The environment of ``env`` / ``optenv``.
        filename: The file being read (None for text input).
        anon: ``$(anon name)``: the run's anonymous name for ``name``.
        evaluate: Evaluates ``$(eval ...)``'s expression with a name lookup.
        math_names: The ``math`` names ``$(eval ...)`` sees.
        length_problem: Given the length a replacement would give the value, what is wrong
            with it (None: nothing).
    """

    args: Mapping[str, str]
    find: Callable[[str], str]
    environ: Mapping[str, str]
    filename: str | None = None
    anon: Callable[[str], str] | None = None
    evaluate: Callable[[str, Lookup], object] | None = None
    math_names: Mapping[str, object] = field(default_factory=dict)
    length_problem: Callable[[int], str | None] | None = None


def collect_args(text: str) -> list[str]:
    """The contents of the ``$(...)`` groups in ``text`` (roslaunch's state machine)."""
    out, dollar, lp, inside = 0, 1, 2, 3
    buff: list[str] = []
    args: list[str] = []
    state = out
    for c in text:
        if c == "$":
            if state == out:
                state = dollar
            elif state != dollar:
                raise SubstitutionError(
                    f'dollar signs "$" cannot be inside of substitution args [{text}]'
                )
        elif c == "(":
            if state == dollar:
                state = lp
            elif state != out:
                raise SubstitutionError(
                    f'invalid left parenthesis "(" in substitution args [{text}]'
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


def safe_evaluator(limits: Limits | None = None) -> Callable[[str, Lookup], object]:
    """``$(eval ...)`` in robomodel's safe evaluator with its own work bounds (``limits``,
    default :class:`~robomodel.xacro.Limits`); errors raise :class:`ExpressionError`
    (``name`` set for an undefined name)."""
    guards = Guards(limits if limits is not None else Limits())

    def run(expr: str, lookup: Lookup) -> object:
        return evaluate(compile_expression(expr.strip()), lookup, guards, guards.functions())

    return run


def resolve_args(text: str, scope: SubstitutionScope, dialect: Dialect) -> str:
    """Resolve every ``$(...)`` in ``text``, as roslaunch's ``resolve_args`` does.

    Raises:
        SubstitutionError: unknown command, unset arg (:class:`ArgNotSet`), unset
            environment variable, no current file for ``$(dirname)``, bad syntax.
        ExpressionError: from ``$(eval ...)``'s evaluator.
    """
    if not text or "$" not in text:
        return text
    if text.startswith("$(eval ") and text.endswith(")"):
        if scope.evaluate is None:
            raise SubstitutionError(f"$(eval ...) is not available here [{text}]")
        return str(scope.evaluate(text[7:-1], _eval_lookup(scope, dialect)))
    first = tuple(c for c in dialect.commands if c != "find" or dialect.find_in_first_pass)
    resolved = _pass(text, scope, dialect, first)
    return _pass(resolved, scope, dialect, ("find",))


def _pass(text: str, scope: SubstitutionScope, dialect: Dialect, commands: tuple[str, ...]) -> str:
    resolved = text
    for a in collect_args(text):
        splits = [s for s in a.split(" ") if s]
        if not splits or splits[0] not in dialect.commands:
            raise SubstitutionError(
                dialect.unknown_command.format(a=a, commands=list(dialect.commands))
            )
        if splits[0] not in commands:
            continue
        value = _command(splits[0], splits[1:], a, scope, dialect)
        count = 1 if splits[0] == "find" and dialect.find_first_only else resolved.count(f"$({a})")
        if scope.length_problem is not None:
            problem = scope.length_problem(len(resolved) + count * (len(value) - len(a) - 3))
            if problem is not None:
                raise SubstitutionError(f"$({a}): {problem}")
        resolved = resolved.replace(f"$({a})", value, count)
    return resolved


def _command(
    command: str, args: list[str], a: str, scope: SubstitutionScope, dialect: Dialect
) -> str:
    if command == "arg":
        if len(args) != 1:
            raise SubstitutionError(dialect.arg_count.format(a=a))
        return _arg(args[0], scope, dialect)
    if command == "find":
        if len(args) != 1:
            raise SubstitutionError(dialect.find_count.format(a=a))
        return scope.find(args[0])
    if command == "env":
        if len(args) != 1:
            raise SubstitutionError(f"$(env var) command only accepts one argument [{a}]")
        return _env(args[0], scope, dialect)
    if command == "optenv":
        if not args:
            raise SubstitutionError(f"$(optenv var) must specify an environment variable [{a}]")
        return scope.environ.get(args[0], " ".join(args[1:]))
    if command == "anon":
        if len(args) != 1:
            raise SubstitutionError(f"$(anon var) must specify exactly one name [{a}]")
        return _anon(args[0], scope)
    return _dirname(scope, dialect)


def _arg(name: str, scope: SubstitutionScope, dialect: Dialect) -> str:
    try:
        return scope.args[name]
    except KeyError:
        raise ArgNotSet.of(name, list(scope.args), dialect) from None


def _env(name: str, scope: SubstitutionScope, dialect: Dialect) -> str:
    try:
        return scope.environ[name]
    except KeyError:
        raise SubstitutionError(dialect.env_unset.format(name=name)) from None


def _anon(name: str, scope: SubstitutionScope) -> str:
    if scope.anon is None:
        raise SubstitutionError(f"$(anon {name}) is not available here")
    return scope.anon(name)


def _dirname(scope: SubstitutionScope, dialect: Dialect) -> str:
    if not scope.filename:
        raise SubstitutionError(dialect.no_dirname)
    return os.path.abspath(os.path.dirname(scope.filename))


def _eval_lookup(scope: SubstitutionScope, dialect: Dialect) -> Lookup:
    functions: dict[str, object] = {
        "arg": lambda name: convert_auto(_arg(name, scope, dialect)),
        "dirname": lambda: _dirname(scope, dialect),
        "env": lambda name: _env(name, scope, dialect),
        "optenv": lambda name, default="": scope.environ.get(name, default),
        "find": scope.find,
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
    if "anon" in dialect.commands:
        functions["anon"] = lambda name: _anon(name, scope)
    functions.update(scope.math_names)

    def lookup(name: str) -> object:
        if name in functions:
            return functions[name]
        return convert_auto(scope.args[name])

    return lookup
