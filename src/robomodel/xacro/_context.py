"""The state of one processing run, and how it turns problems into located diagnostics.

The reference keeps this state in module globals (``filestack``, ``macrostack``,
``all_includes``, ``substitution_args_context``), so it is not re-entrant and leaks arg defaults
between calls. Here everything lives in one :class:`Context` per run.
"""

from __future__ import annotations

import os
import re
from collections.abc import Mapping
from dataclasses import dataclass, field

from robomodel.description.packages import PackageIndex
from robomodel.errors import Diagnostic, InputError, PackageNotFoundError, Severity, SourceLocation
from robomodel.xacro._dom import Node, Text
from robomodel.xacro._safe_eval import Guards, Limits

__all__ = ["Context", "Frame"]

_MAX_NOTES = 12


@dataclass(frozen=True, slots=True)
class Frame:
    """One level of the include/macro stack, for error notes.

    Attributes:
        kind: ``"macro"`` or ``"include"``.
        name: The macro name or the included file.
        defined: Where the macro is defined (None for includes).
        site: The calling element or the ``<xacro:include>`` element.
    """

    kind: str
    name: str
    defined: SourceLocation | None
    site: Node

    @property
    def called(self) -> SourceLocation:
        """Where the macro is called or the file is included from."""
        loc = self.site.loc
        return SourceLocation(loc[0], loc[1] or None, loc[2] or None)

    def describe(self) -> str:
        """``in macro 'wheel' (robot.xacro:41), called from robot.xacro:88``."""
        if self.kind == "macro":
            where = f" ({_short(self.defined)})" if self.defined else ""
            return f"in macro '{self.name}'{where}, called from {_short(self.called)}"
        return f"in file {self.name}, included from {_short(self.called)}"


def _short(location: SourceLocation | None) -> str:
    if location is None:
        return "?"
    path = os.path.basename(location.path) if location.path else "<string>"
    return f"{path}:{location.line}" if location.line else path


class ArgValues(dict[str, str]):
    """``xacro:arg`` values that remember which names ``$(arg name)`` read."""

    def __init__(self, values: Mapping[str, str]) -> None:
        super().__init__(values)
        self.read: set[str] = set()

    def __getitem__(self, name: str) -> str:
        value = super().__getitem__(name)
        self.read.add(name)
        return value


@dataclass
class Context:
    """Everything one expansion needs and produces.

    Attributes:
        args: Values of ``xacro:arg`` and ``name:=value`` (a private copy of the mappings).
        package_index: Resolves ``$(find pkg)``.
        root_dir: Base for relative paths of string input, the input file and ``$(cwd)``.
        limits: Evaluation and expansion bounds.
        environ: Environment for ``$(env)`` and ``$(optenv)``.
    """

    args: ArgValues
    package_index: PackageIndex
    root_dir: str = os.curdir
    limits: Limits = field(default_factory=Limits)
    environ: Mapping[str, str] = field(default_factory=lambda: dict(os.environ))
    filestack: list[str | None] = field(default_factory=list)
    stack: list[Frame] = field(default_factory=list)
    includes: list[str] = field(default_factory=list)
    diagnostics: list[Diagnostic] = field(default_factory=list)
    sources: dict[str | None, bytes] = field(default_factory=dict)
    node: Node | None = None
    attr: str | None = None
    nodes_left: int = 0
    work_left: int = 0
    guards: Guards = field(init=False)
    base: dict[str, object] = field(init=False)
    globals: dict[str, object] = field(default_factory=dict)
    empty_text: Text = field(init=False)
    declared_args: set[str] = field(default_factory=set)  # names of the xacro:arg tags seen

    def __post_init__(self) -> None:
        self.guards = Guards(self.limits)
        self.base = self.guards.functions()
        # The reference moves one shared '\n\n' text node around to stop comment removal
        # (remove_previous_comments); its position changes the layout, so it is mirrored.
        self.empty_text = Text("\n\n")
        self.nodes_left = self.limits.max_nodes
        self.work_left = self.limits.max_work

    @property
    def current_file(self) -> str | None:
        """The file being processed."""
        return self.filestack[-1] if self.filestack else None

    def find_package(self, name: str) -> str:
        """``$(find name)``."""
        try:
            return str(self.package_index.find(name))
        except PackageNotFoundError as exc:
            raise self.error(str(exc)) from None

    def record_include(self, path: str) -> None:
        """Remember a dependency for ``--deps`` (in first-seen order)."""
        if path not in self.includes:
            self.includes.append(path)

    def location(
        self, node: Node | None = None, attr: str | None = None, needle: str | None = None
    ) -> SourceLocation:
        """The position of ``node``, of its attribute ``attr``, or of ``needle`` inside them."""
        node = node if node is not None else self.node
        if node is None:
            return SourceLocation(self.current_file)
        source = self.sources.get(node.file)
        if source is not None and node.offset >= 0:
            pos = self._source_position(node, source, attr, needle)
            if pos is not None:
                line = source.count(b"\n", 0, pos) + 1
                column = pos - (source.rfind(b"\n", 0, pos) + 1) + 1
                return SourceLocation(node.file, line, column)
        return SourceLocation(node.file, node.line or None, node.column or None)

    @staticmethod
    def _source_position(
        node: Node, source: bytes, attr: str | None, needle: str | None
    ) -> int | None:
        """Byte offset of the attribute or text (and of ``needle`` in it) in ``source``."""
        wanted = needle.encode() if needle else b""
        if type(node) is Text:
            # A text node's offset is where it ends; it cannot contain '<'.
            end = node.offset
            start = source.rfind(b"<", 0, end)
            start = source.find(b">", start) + 1 if start >= 0 else 0
            found = source.find(wanted, start, end) if wanted else -1
            if found >= 0:
                return found
            while start < end and source[start : start + 1].isspace():
                start += 1
            return start
        if attr is None:
            return None
        pattern = re.compile(rb"\s(" + re.escape(attr.encode()) + rb")\s*=")
        match = pattern.search(source, node.offset)
        if match is None:
            return None
        pos = match.start(1)
        if wanted:
            found = source.find(wanted, pos, pos + 4096)
            if found >= 0:
                return found
        return pos

    def notes(self) -> list[Diagnostic]:
        """The stack as notes, innermost first; deep recursion is elided in the middle."""
        frames = list(reversed(self.stack))
        notes = [Diagnostic(Severity.NOTE, f.describe(), f.called) for f in frames]
        if len(notes) > _MAX_NOTES:
            head, tail = notes[: _MAX_NOTES // 2], notes[-(_MAX_NOTES // 2) :]
            skipped = len(notes) - len(head) - len(tail)
            elided = Diagnostic(Severity.NOTE, f"... {skipped} more frames ...", head[-1].location)
            notes = [*head, elided, *tail]
        return notes

    def error(
        self,
        message: str,
        node: Node | None = None,
        attr: str | None = None,
        *,
        needle: str | None = None,
    ) -> InputError:
        """Build an error at ``node``/``attr`` (default: the node being evaluated), pointing at
        ``needle`` (the offending ``${...}``) when it can be found in the source."""
        if node is None and attr is None:
            attr = self.attr
        location = self.location(node, attr, needle)
        return InputError(Diagnostic(Severity.ERROR, message, location), notes=self.notes())

    def warn(
        self, message: str, node: Node | None = None, severity: Severity = Severity.WARNING
    ) -> None:
        """Record a warning (printed by the CLI, returned by the API)."""
        self.diagnostics.append(Diagnostic(severity, message, self.location(node)))

    def charge_work(self, units: int) -> None:
        """Account for ``units`` of expansion work (see ``Limits.max_work``); refuse runaway
        expansions (exponential macro fan-out, strings doubling per property) early, at the
        node being expanded and with the macro stack, instead of after minutes."""
        self.work_left -= units
        if self.work_left < 0:
            raise self.error(
                f"expansion does more than {self.limits.max_work} units of work (macro calls, "
                "created nodes, evaluated text); does a macro call itself more than once per "
                "level, or a property double in length at each step?"
            )

    def charge_nodes(self, count: int) -> None:
        """Account for ``count`` nodes created by an expansion; refuse runaway growth."""
        self.charge_work(count + 1)
        self.nodes_left -= count
        if self.nodes_left < 0:
            raise self.error(
                f"expansion creates more than {self.limits.max_nodes} nodes; "
                "is a macro or block recursing without end?"
            )
