"""The exception hierarchy and located diagnostics shared by every layer.

Every error that robomodel raises derives from :class:`RobomodelError`. Errors about an input
file carry a :class:`SourceLocation` so that the CLI can print ``file:line:column: error: ...``.
"""

from __future__ import annotations

import enum
from collections.abc import Iterable, Sequence
from dataclasses import dataclass

__all__ = [
    "Diagnostic",
    "InputError",
    "MissingDependencyError",
    "PackageNotFoundError",
    "PathEscapeError",
    "RobomodelError",
    "Severity",
    "SourceLocation",
    "close_matches",
    "describe_unknown",
]


class Severity(enum.Enum):
    """How bad a diagnostic is."""

    ERROR = "error"
    WARNING = "warning"
    NOTE = "note"


@dataclass(frozen=True, slots=True)
class SourceLocation:
    """A position in an input file. Lines and columns are 1-based, as editors show them."""

    path: str | None
    line: int | None = None
    column: int | None = None

    def __str__(self) -> str:
        parts = [self.path or "<string>"]
        if self.line is not None:
            parts.append(str(self.line))
            if self.column is not None:
                parts.append(str(self.column))
        return ":".join(parts)


@dataclass(frozen=True, slots=True)
class Diagnostic:
    """One message about an input, with where it applies and a stable rule code."""

    severity: Severity
    message: str
    location: SourceLocation
    code: str = ""

    def format(self) -> str:
        """Return the ``file:line:column: severity: message`` line compilers print."""
        return f"{self.location}: {self.severity.value}: {self.message}"

    def as_dict(self) -> dict[str, object]:
        """Return a JSON-friendly dictionary."""
        return {
            "severity": self.severity.value,
            "message": self.message,
            "path": self.location.path,
            "line": self.location.line,
            "column": self.location.column,
            "code": self.code,
        }


class RobomodelError(Exception):
    """Root of every exception robomodel raises on purpose."""


class InputError(RobomodelError):
    """An input file is invalid. Carries the fatal diagnostic and any collected before it."""

    def __init__(self, diagnostic: Diagnostic, *, notes: Sequence[Diagnostic] = ()) -> None:
        super().__init__(diagnostic.format())
        self.diagnostic = diagnostic
        self.notes = tuple(notes)

    @property
    def message(self) -> str:
        return self.diagnostic.message

    @property
    def path(self) -> str | None:
        return self.diagnostic.location.path

    @property
    def line(self) -> int | None:
        return self.diagnostic.location.line

    @property
    def column(self) -> int | None:
        return self.diagnostic.location.column

    @classmethod
    def at(
        cls,
        message: str,
        path: str | None,
        line: int | None = None,
        column: int | None = None,
        *,
        code: str = "",
    ) -> InputError:
        """Build an error at a location in one call."""
        loc = SourceLocation(path, line, column)
        return cls(Diagnostic(Severity.ERROR, message, loc, code))


def close_matches(word: str, candidates: Iterable[str], n: int = 3) -> list[str]:
    """Return up to ``n`` candidates that look like ``word`` (for "did you mean" hints)."""
    import difflib  # only when an error message is built (keeps start-up short)

    return difflib.get_close_matches(word, list(candidates), n=n, cutoff=0.6)


def describe_unknown(what: str, name: str, available: Sequence[str], listing: str) -> str:
    """``"<what> 'name' (did you mean 'x'?); <listing>: a, b"`` for an unknown name."""
    message = f"{what} '{name}'"
    hint = close_matches(name, available)
    if hint:
        message += f" (did you mean {', '.join(repr(h) for h in hint)}?)"
    return message + f"; {listing}: {', '.join(available) or '(none)'}"


class PackageNotFoundError(RobomodelError):
    """A ROS package name (``package://name`` or ``$(find name)``) is not known."""

    def __init__(self, name: str, available: Sequence[str], searched: Sequence[str]) -> None:
        self.name = name
        self.available = tuple(available)
        self.searched = tuple(searched)
        hint = close_matches(name, self.available)
        msg = f"package '{name}' not found"
        if hint:
            msg += f" (did you mean {', '.join(repr(h) for h in hint)}?)"
        if searched:
            msg += f"; searched: {'; '.join(searched)}"
        else:
            msg += "; no package paths given"
        msg += (
            ". Add the folder that holds it with --package-path DIR or ROS_PACKAGE_PATH=DIR "
            f"(AMENT_PREFIX_PATH for an installed ROS 2 prefix), or name it: --package {name}=DIR"
        )
        super().__init__(msg)


class PathEscapeError(RobomodelError):
    """A path inside a package resolves outside that package's directory."""

    def __init__(self, uri: str, package: str, package_dir: str) -> None:
        self.uri = uri
        self.package = package
        self.package_dir = package_dir
        super().__init__(
            f"'{uri}' escapes package '{package}' ({package_dir}); "
            "paths inside a package may not leave its directory"
        )


class MissingDependencyError(RobomodelError):
    """An optional dependency is not installed."""

    def __init__(self, module: str, extra: str, purpose: str) -> None:
        self.module = module
        self.extra = extra
        super().__init__(
            f"{purpose} needs the '{module}' package: pip install 'robomodel[{extra}]'"
        )
