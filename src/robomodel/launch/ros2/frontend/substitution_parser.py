"""The ``$(name arg ...)`` substitution syntax of XML/YAML launch files (launch's grammar).

Text outside ``$(...)`` is literal; inside, arguments are separated by spaces and may be
single- or double-quoted (quotes may contain substitutions) or nest further ``$(...)``.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from robomodel.launch.ros2.shim import commands as c
from robomodel.launch.ros2.shim import logic as b
from robomodel.launch.ros2.shim import substitutions as s
from robomodel.launch.ros2.shim.context import SubstitutionFailure

__all__ = ["SUBSTITUTIONS", "parse_substitution"]

Args = list[list[s.Substitution]]


def _n(name: str, args: Args, low: int, high: int) -> None:
    if not low <= len(args) <= high:
        expected = str(low) if low == high else f"{low} to {high}"
        raise SubstitutionFailure(
            f"{name} substitution expects {expected} argument(s), got {len(args)}"
        )


def _var(a: Args) -> s.Substitution:
    _n("var", a, 1, 2)
    return s.LaunchConfiguration(a[0], default=a[1] if len(a) == 2 else None)


def _env(a: Args) -> s.Substitution:
    _n("env", a, 1, 2)
    return s.EnvironmentVariable(a[0], default_value=a[1] if len(a) == 2 else None)


def _command(a: Args) -> s.Substitution:
    _n("command", a, 1, 2)
    return c.Command(a[0], on_stderr=a[1] if len(a) == 2 else "fail")


def _eval(a: Args) -> s.Substitution:
    _n("eval", a, 1, 2)
    if len(a) == 2:
        modules = "".join(x.text for x in a[1] if isinstance(x, s.TextSubstitution))
        return c.PythonExpression(a[0], [m.strip() for m in modules.split(",") if m.strip()])
    return c.PythonExpression(a[0])


def _one(cls: Callable[[Any], s.Substitution], name: str) -> Callable[[Args], s.Substitution]:
    def make(a: Args) -> s.Substitution:
        _n(name, a, 1, 1)
        return cls(a[0])

    return make


def _two(cls: Callable[[Any, Any], s.Substitution], name: str) -> Callable[[Args], s.Substitution]:
    def make(a: Args) -> s.Substitution:
        _n(name, a, 2, 2)
        return cls(a[0], a[1])

    return make


def _none(cls: Callable[[], s.Substitution], name: str) -> Callable[[Args], s.Substitution]:
    def make(a: Args) -> s.Substitution:
        _n(name, a, 0, 0)
        return cls()

    return make


def _if(a: Args) -> s.Substitution:
    _n("if", a, 1, 3)
    return b.IfElseSubstitution(*a)


SUBSTITUTIONS: dict[str, Callable[[Args], s.Substitution]] = {
    "var": _var,
    "env": _env,
    "command": _command,
    "eval": _eval,
    "find-pkg-share": _one(c.FindPackageShare, "find-pkg-share"),
    "find-pkg-prefix": _one(c.FindPackagePrefix, "find-pkg-prefix"),
    "find-exec": _one(lambda x: s.FindExecutable(name=x), "find-exec"),
    "exec-in-pkg": _two(c.ExecutableInPackage, "exec-in-pkg"),
    "dirname": _none(s.ThisLaunchFileDir, "dirname"),
    "filename": _none(s.ThisLaunchFile, "filename"),
    "anon": _one(s.AnonName, "anon"),
    "not": _one(b.NotSubstitution, "not"),
    "and": _two(b.AndSubstitution, "and"),
    "or": _two(b.OrSubstitution, "or"),
    "equals": _two(b.EqualsSubstitution, "equals"),
    "not-equals": _two(b.NotEqualsSubstitution, "not-equals"),
    "file-content": _one(s.FileContent, "file-content"),
    "if": _if,
    "all": lambda a: b.AllSubstitution(*a),
    "any": lambda a: b.AnySubstitution(*a),
}


class _Parser:
    def __init__(self, text: str) -> None:
        self.text = text
        self.pos = 0

    def error(self, message: str) -> SubstitutionFailure:
        return SubstitutionFailure(f"{message} at character {self.pos + 1} of '{self.text}'")

    def template(self, stop: str = "") -> list[s.Substitution]:
        parts: list[s.Substitution] = []
        buf: list[str] = []
        text = self.text
        while self.pos < len(text):
            ch = text[self.pos]
            if stop and ch in stop:
                break
            if ch == "\\" and self.pos + 1 < len(text) and text[self.pos + 1] in "$\\'\"":
                buf.append(text[self.pos + 1])
                self.pos += 2
            elif text.startswith("$(", self.pos):
                if buf:
                    parts.append(s.TextSubstitution(text="".join(buf)))
                    buf = []
                parts.append(self.substitution())
            else:
                buf.append(ch)
                self.pos += 1
        if buf:
            parts.append(s.TextSubstitution(text="".join(buf)))
        return parts

    def substitution(self) -> s.Substitution:
        self.pos += 2
        start = self.pos
        while self.pos < len(self.text) and (
            self.text[self.pos].isalnum() or self.text[self.pos] in "-_"
        ):
            self.pos += 1
        name = self.text[start : self.pos]
        if not name:
            raise self.error("expected a substitution name after '$('")
        args: Args = []
        while True:
            while self.pos < len(self.text) and self.text[self.pos] in " \t\n":
                self.pos += 1
            if self.pos >= len(self.text):
                raise self.error(f"unterminated '$({name}'")
            if self.text[self.pos] == ")":
                self.pos += 1
                break
            args.append(self.argument())
        if name not in SUBSTITUTIONS:
            raise SubstitutionFailure(
                f"unknown substitution '$({name})'; known: {', '.join(sorted(SUBSTITUTIONS))}"
            )
        return SUBSTITUTIONS[name](args)

    def argument(self) -> list[s.Substitution]:
        parts: list[s.Substitution] = []
        while self.pos < len(self.text) and self.text[self.pos] not in " \t\n)":
            quote = self.text[self.pos]
            if quote in "'\"":
                self.pos += 1
                parts.extend(self.template(stop=quote))
                if self.pos >= len(self.text):
                    raise self.error("unterminated quote")
                self.pos += 1
            else:
                parts.extend(self.template(stop=" \t\n)'\""))
        return parts or [s.TextSubstitution(text="")]


def parse_substitution(text: str) -> list[s.Substitution]:
    """Parse launch-file text into substitutions (plain text gives one TextSubstitution)."""
    if not text:
        return [s.TextSubstitution(text="")]
    return _Parser(text).template()
