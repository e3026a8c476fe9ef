"""The roslaunch loader's shared machinery: locations, errors, substitution, attribute
checks, ``if``/``unless``, file parsing and the scoping of namespaces and ``clear_params``."""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

from lxml import etree

from robomodel._files import UserFileError, read_user_bytes
from robomodel.description.packages import PackageIndex
from robomodel.errors import PackageNotFoundError, SourceLocation
from robomodel.launch.bounds import work_exceeded
from robomodel.launch.model import LaunchError, NodeSpec
from robomodel.launch.processes import COMMAND_TIMEOUT_S
from robomodel.launch.ros1.attr_values import loose_bool, strict_bool
from robomodel.launch.ros1.config import MachineSpec, ParamDump
from robomodel.launch.ros1.context import LoaderContext
from robomodel.launch.ros1.names import (
    make_global_ns,
    ns_join,
)
from robomodel.launch.ros1.substitution import (
    ArgNotSet,
    SubstitutionContext,
    SubstitutionError,
    resolve,
)

__all__ = ["LoaderBase"]

_MAX_INCLUDE_DEPTH = 64
_NODE_ATTRS = (
    "pkg", "type", "machine", "name", "args", "output", "respawn", "respawn_delay", "cwd",
    "ns", "clear_params", "launch-prefix", "required",
)  # fmt: skip
_TEST_ATTRS = (*_NODE_ATTRS, "test-name", "time-limit", "retry")
_PARAM_ATTRS = ("name", "value", "type", "textfile", "binfile", "command")
_ROSPARAM_ATTRS = ("command", "ns", "file", "param", "subst_value")
_ARG_ATTRS = ("name", "value", "default", "doc")
_INCLUDE_ATTRS = ("file", "ns", "clear_params", "pass_all_args")
_GROUP_ATTRS = ("ns", "clear_params")
_MACHINE_ATTRS = (
    "name", "address", "env-loader", "ssh-port", "user", "password", "default", "timeout",
)  # fmt: skip


class LoaderBase:
    """What every tag handler of the loader uses."""

    def __init__(
        self,
        packages: PackageIndex,
        environ: Mapping[str, str],
        *,
        command_timeout_s: float = COMMAND_TIMEOUT_S,
    ) -> None:
        self.packages = packages
        self.environ = environ
        self.command_timeout_s = command_timeout_s
        self.work = 0  # elements and includes processed (the fan-out bound)
        self.params: dict[str, Any] = {}
        self.nodes: list[NodeSpec] = []
        self.tests: list[NodeSpec] = []
        self.clear_params: list[str] = []
        self.deletes: list[str] = []
        self.dumps: list[ParamDump] = []
        self.machines: list[MachineSpec] = []
        self.files: list[Path] = []
        self.warnings: list[str] = []
        self.stack: list[SourceLocation] = []
        self.anons: dict[str, str] = {}
        self.declared_args: dict[str, None] = {}  # every <arg> name of every file, in order
        self.sources: dict[str, list[str]] = {}
        self.root: LoaderContext | None = None

    # -- locations and errors -------------------------------------------------------------
    def where(self, element: Any, filename: str | None, attr: str | None = None) -> SourceLocation:
        line = element.sourceline if element is not None else None
        column = None
        lines = self.sources.get(filename or "")
        if line is not None and lines and 0 < line <= len(lines):
            text = lines[line - 1]
            tag = f"<{element.tag}"
            col = text.find(tag)
            if attr is not None:
                at = text.find(f"{attr}=", max(col, 0))
                col = at if at >= 0 else col
            column = col + 1 if col >= 0 else 1
        return SourceLocation(filename, line, column)

    def error(
        self, message: str, element: Any, ctx: LoaderContext, attr: str | None = None
    ) -> LaunchError:
        return LaunchError(
            message,
            location=self.where(element, ctx.filename, attr),
            include_stack=tuple(self.stack),
        )

    def charge(self, units: int, element: Any, ctx: LoaderContext) -> None:
        """Count ``units`` of work; past the bound (robomodel.launch.bounds) the launch is
        refused."""
        self.work += units
        problem = work_exceeded(self.work, "element", len(self.files))
        if problem is not None:
            raise self.error(problem, element, ctx)

    # -- attributes -----------------------------------------------------------------------
    def subst(self, text: str | None, ctx: LoaderContext) -> str | None:
        sub = SubstitutionContext(
            ctx.args, self.find, self.environ, filename=ctx.filename, anons=self.anons
        )
        return resolve(text, sub)

    def find(self, name: str) -> str:
        try:
            return str(self.packages.find(name))
        except PackageNotFoundError as exc:
            raise SubstitutionError(str(exc)) from None

    def attr(self, element: Any, name: str, ctx: LoaderContext) -> str | None:
        value = element.get(name)
        try:
            return self.subst(value, ctx)
        except ArgNotSet:
            raise
        except SubstitutionError as exc:
            raise self.error(str(exc), element, ctx, name) from None

    def required(self, element: Any, name: str, ctx: LoaderContext) -> str:
        if element.get(name) is None:
            raise self.error(
                f"<{element.tag}> tag is missing required attribute: '{name}'", element, ctx
            )
        value = self.attr(element, name, ctx)
        assert value is not None
        return value

    def check_attrs(self, element: Any, ctx: LoaderContext, allowed: tuple[str, ...]) -> None:
        for name in element.attrib:
            if name not in allowed and name not in ("if", "unless"):
                self.warnings.append(
                    f"{self.where(element, ctx.filename, name)}: unknown <{element.tag}> "
                    f"attribute '{name}'; valid attributes are {', '.join(allowed)}"
                )

    def enabled(self, element: Any, ctx: LoaderContext) -> bool:
        """roslaunch's ``ifunless``: ``if`` and ``unless`` together is an error; the value is
        read with the loose bool rule (``1``/``0`` too)."""
        if_value, unless_value = element.get("if"), element.get("unless")
        if if_value is not None and unless_value is not None:
            raise self.error("cannot set both 'if' and 'unless' on the same tag", element, ctx)
        try:
            if if_value is not None:
                return loose_bool(self.attr(element, "if", ctx) or "", "if")
            if unless_value is not None:
                return not loose_bool(self.attr(element, "unless", ctx) or "", "unless")
        except ValueError as exc:
            raise self.error(str(exc), element, ctx) from None
        return True

    # -- files ----------------------------------------------------------------------------
    def parse(self, filename: str, element: Any, ctx: LoaderContext | None) -> Any:
        path = Path(filename)
        try:
            data = read_user_bytes(path, what="launch file")
        except UserFileError as exc:
            message = str(exc)
            if ctx is None or element is None:
                raise LaunchError(message, include_stack=tuple(self.stack)) from None
            raise self.error(message, element, ctx, "file") from None
        if b"<!ENTITY" in data and b"<!DOCTYPE" in data:
            line = data[: data.find(b"<!ENTITY")].count(b"\n") + 1
            raise LaunchError(
                "entity declarations are not allowed in launch files (expansion bombs, "
                "reading local files)",
                location=SourceLocation(filename, line, 1),
                include_stack=tuple(self.stack),
            )
        parser = etree.XMLParser(
            resolve_entities=False, no_network=True, load_dtd=False, huge_tree=False
        )
        try:
            root = etree.fromstring(data, parser)
        except etree.XMLSyntaxError as exc:
            line, column = exc.position if exc.position else (1, 1)
            message = (exc.msg or "malformed XML").rsplit(", line ", 1)[0]
            raise LaunchError(
                f"Invalid roslaunch XML syntax: {message}",
                location=SourceLocation(filename, line, column),
                include_stack=tuple(self.stack),
            ) from None
        self.sources[filename] = data.decode("utf-8", "replace").splitlines()
        if root.tag != "launch":
            raise LaunchError(
                f"Invalid roslaunch XML syntax: no root <launch> tag (the root is <{root.tag}>)",
                location=SourceLocation(filename, root.sourceline, 1),
                include_stack=tuple(self.stack),
            )
        self.files.append(path)
        return root

    # -- tags -----------------------------------------------------------------------------
    def ns_clear_params(
        self,
        tag: str,
        element: Any,
        ctx: LoaderContext,
        node_name: str | None = None,
        include_filename: str | None = None,
    ) -> LoaderContext:
        ns = None
        if element.get("ns") is not None:
            ns = self.attr(element, "ns", ctx)
            if not ns:
                raise self.error(f"<{tag}> tag has an empty 'ns' attribute", element, ctx, "ns")
        try:
            child = (
                ctx.include_child(ns, include_filename)
                if include_filename is not None
                else ctx.child(ns)
            )
        except ValueError as exc:
            raise self.error(str(exc), element, ctx, "ns") from None
        clear = self.attr(element, "clear_params", ctx)
        try:
            if clear and strict_bool(clear, False, "clear_params"):
                if tag == "node":
                    if not node_name:
                        raise ValueError(
                            f"<{tag}> tag must have a 'name' attribute to use 'clear_params'"
                        )
                    self.clear_params.append(make_global_ns(ns_join(child.ns, node_name)))
                else:
                    if not ns:
                        raise ValueError(
                            "'ns' attribute must be set in order to use 'clear_params'"
                        )
                    self.clear_params.append(child.ns)
        except ValueError as exc:
            raise self.error(str(exc), element, ctx, "clear_params") from None
        return child
