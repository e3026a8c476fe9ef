"""The public entry points: ``process_file``, ``process``, ``expand``."""

from __future__ import annotations

import os
from collections.abc import Mapping
from dataclasses import dataclass

from robomodel._files import UserFileError
from robomodel._gc import paused_gc
from robomodel.description.packages import PackageIndex
from robomodel.errors import (
    Diagnostic,
    InputError,
    RobomodelError,
    Severity,
    SourceLocation,
    close_matches,
)
from robomodel.xacro._calls import read_document
from robomodel.xacro._context import ArgValues, Context
from robomodel.xacro._dom import Document
from robomodel.xacro._evaluation import build_globals
from robomodel.xacro._parse import parse_xml
from robomodel.xacro._processor import process_document
from robomodel.xacro._safe_eval import Limits
from robomodel.xacro._serialize import SerializationError, serialize

TYPE_CHECKING = False  # typing.TYPE_CHECKING without importing typing (start-up)
if TYPE_CHECKING:
    from typing import IO

__all__ = ["ExpansionResult", "XacroDocument", "expand", "process", "process_file"]


@dataclass(frozen=True, slots=True)
class XacroDocument:
    """An expanded document with minidom's writer methods.

    Attributes:
        document: The expanded tree.
        banner_for: The input name shown in the banner (None: no banner, as for text input).
        includes: Included and loaded files in first-use order.
        warnings: Warnings and messages produced while expanding.
        max_output_chars: Printing a larger document raises :class:`RobomodelError`.
    """

    document: Document
    banner_for: str | None
    includes: tuple[str, ...]
    warnings: tuple[Diagnostic, ...]
    max_output_chars: int = Limits().max_output_chars

    def toprettyxml(self, indent: str = "\t", newl: str = "\n") -> str:
        """The text ``minidom.Document.toprettyxml`` gives with xacro's writer."""
        try:
            with paused_gc():
                return serialize(
                    self.document,
                    indent=indent,
                    newl=newl,
                    banner_for=self.banner_for,
                    max_chars=self.max_output_chars,
                )
        except SerializationError as exc:
            raise RobomodelError(str(exc)) from None
        except RecursionError:
            raise RobomodelError("document nested too deeply to print") from None

    def toxml(self) -> str:
        """The compact text (``minidom.Document.toxml``)."""
        return self.toprettyxml(indent="", newl="")


@dataclass(frozen=True, slots=True)
class ExpansionResult:
    """What ``robomodel xacro`` prints, and what it depends on.

    Attributes:
        text: The output exactly as the CLI writes it.
        includes: Dependencies (included files and YAML files) in first-use order.
        warnings: Warnings and messages produced while expanding.
    """

    text: str
    includes: tuple[str, ...]
    warnings: tuple[Diagnostic, ...]


def _context(
    mappings: Mapping[str, str] | None,
    package_index: PackageIndex | None,
    root_dir: str | os.PathLike[str] | None,
    limits: Limits | None,
) -> Context:
    ctx = Context(
        args=ArgValues({str(k): str(v) for k, v in (mappings or {}).items()}),
        package_index=package_index if package_index is not None else PackageIndex(),
        root_dir=os.fspath(root_dir) if root_dir else os.curdir,
        limits=limits or Limits(),
    )
    ctx.globals = build_globals(ctx)
    return ctx


def _warn_undeclared(ctx: Context, given: tuple[str, ...], source: str | None) -> None:
    """A ``name:=value`` no ``xacro:arg`` declares and no ``$(arg)`` reads: xacro ignores it
    silently, which hides a typo (``robomodel xacro robot.xacro prefx:=left_``)."""
    declared = sorted(ctx.declared_args)
    for name in given:
        if name in ctx.declared_args or name in ctx.args.read or name.startswith("_"):
            continue
        hint = close_matches(name, declared)
        mean = f" (did you mean {', '.join(repr(h) for h in hint)}?)" if hint else ""
        message = (
            f'{name}:=... is ignored: no <xacro:arg name="{name}"> declares it{mean}; '
            f"declared args: {', '.join(declared) or '(none)'}"
        )
        ctx.diagnostics.append(Diagnostic(Severity.WARNING, message, SourceLocation(source)))


def _run(ctx: Context, document: Document, banner_for: str | None) -> XacroDocument:
    given = tuple(ctx.args)
    try:
        with paused_gc():
            process_document(ctx, document)
    except RecursionError:
        raise ctx.error("expansion nested too deeply (recursion limit)") from None
    _warn_undeclared(ctx, given, banner_for)
    return XacroDocument(
        document,
        banner_for,
        tuple(ctx.includes),
        tuple(ctx.diagnostics),
        ctx.limits.max_output_chars,
    )


def process_file(
    path: str | os.PathLike[str],
    mappings: Mapping[str, str] | None = None,
    *,
    package_index: PackageIndex | None = None,
    root_dir: str | os.PathLike[str] | None = None,
    limits: Limits | None = None,
    **ignored: object,
) -> XacroDocument:
    """Expand a xacro file, like the reference ``xacro.process_file``.

    Args:
        path: The input file (relative paths are relative to ``root_dir``, default cwd).
        mappings: ``name -> value`` for ``xacro:arg`` (never modified).
        package_index: Resolves ``$(find pkg)``; default reads ROS_PACKAGE_PATH and
            AMENT_PREFIX_PATH.
        root_dir: Base directory for relative paths and ``$(cwd)``.
        limits: Evaluation and expansion bounds.
        **ignored: Reference options without effect here (``verbosity``, ``xacro_ns``, ...).

    Returns:
        The expanded document; ``.toprettyxml(indent="  ")`` gives the CLI's bytes.

    Raises:
        InputError: for any problem in the input, located at file:line:column.
    """
    name = os.fspath(path)
    ctx = _context(mappings, package_index, root_dir, limits)
    ctx.filestack.append(name)
    with paused_gc():
        try:
            document = read_document(ctx, name)
        except UserFileError as exc:
            raise InputError.at(exc.reason, name) from None
        return _run(ctx, document, name)


def process(
    source: str | os.PathLike[str] | IO[str],
    mappings: Mapping[str, str] | None = None,
    *,
    package_index: PackageIndex | None = None,
    root_dir: str | os.PathLike[str] | None = None,
    limits: Limits | None = None,
    **ignored: object,
) -> str:
    """Expand a file path or XML text and return the pretty-printed output.

    A ``source`` starting with ``<`` (after whitespace), or an open file, is XML text: it is processed like the
    reference's ``process_doc`` (includes relative to ``root_dir``) and printed without banner.
    Anything else is a path, processed as :func:`process_file` and printed as the CLI does.
    """
    if hasattr(source, "read"):
        source = str(source.read())  # a file object, as the reference's parse() accepts
    text = os.fspath(source)
    if text.lstrip().startswith("<"):
        ctx = _context(mappings, package_index, root_dir, limits)
        ctx.filestack.append(None)
        ctx.sources[None] = text.encode("utf-8")
        document = parse_xml(text, None)
        return _run(ctx, document, None).toprettyxml(indent="  ")
    return process_file(
        text, mappings, package_index=package_index, root_dir=root_dir, limits=limits
    ).toprettyxml(indent="  ")


def expand(
    path: str | os.PathLike[str],
    *,
    mappings: Mapping[str, str] | None = None,
    package_index: PackageIndex | None = None,
    root_dir: str | os.PathLike[str] | None = None,
    limits: Limits | None = None,
) -> ExpansionResult:
    """Expand a xacro file and return the CLI's output text with its dependencies."""
    doc = process_file(
        path, mappings, package_index=package_index, root_dir=root_dir, limits=limits
    )
    return ExpansionResult(doc.toprettyxml(indent="  "), doc.includes, doc.warnings)
