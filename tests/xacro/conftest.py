"""Helpers to run the reference xacro 2.1.1 in-process and compare its bytes with ours."""

from __future__ import annotations

import contextlib
import io
import os
from collections.abc import Iterator, Mapping
from pathlib import Path

import pytest

from robomodel import xacro as rx
from robomodel.description.packages import PackageIndex

REPO = Path(__file__).resolve().parents[2]
EXAMPLES = REPO / "examples"


def example_index() -> PackageIndex:
    """The package index of the examples directory only."""
    return PackageIndex(package_paths=[EXAMPLES], use_environment=False)


@contextlib.contextmanager
def _reference(index: PackageIndex | None) -> Iterator[object]:
    """Import the reference, reset its global state and point ``$(find)`` at ``index``."""
    xacro = pytest.importorskip("xacro")
    import xacro.substitution_args as sa  # type: ignore[import-untyped]

    old_find = sa._eval_find
    sa._eval_find = (lambda pkg: str(index.find(pkg))) if index else old_find
    xacro.all_includes = []
    xacro.filestack = None
    xacro.macrostack = None
    xacro.root_dir = os.curdir
    try:
        with contextlib.redirect_stderr(io.StringIO()):
            yield xacro
    finally:
        sa._eval_find = old_find
        xacro.filestack = None


def reference_text(text: str, mappings: Mapping[str, str] | None = None) -> str:
    """The reference's ``parse`` + ``process_doc`` + ``toprettyxml`` on a string."""
    with _reference(None) as xacro:
        doc = xacro.parse(text)  # type: ignore[attr-defined]
        xacro.process_doc(doc, mappings=dict(mappings or {}))  # type: ignore[attr-defined]
        return str(doc.toprettyxml(indent="  "))


def reference_file(
    path: str | Path,
    mappings: Mapping[str, str] | None = None,
    index: PackageIndex | None = None,
) -> str:
    """What the reference CLI prints for ``path``."""
    with _reference(index) as xacro:
        doc = xacro.process_file(str(path), mappings=dict(mappings or {}))  # type: ignore[attr-defined]
        return str(doc.toprettyxml(indent="  "))


def reference_deps(path: str | Path, index: PackageIndex | None = None) -> list[str]:
    """The reference's dependency list (unordered in its CLI) after processing ``path``."""
    with _reference(index) as xacro:
        xacro.process_file(str(path), mappings={})  # type: ignore[attr-defined]
        return list(xacro.all_includes)  # type: ignore[attr-defined]


def ours_text(text: str, mappings: Mapping[str, str] | None = None) -> str:
    """Our output for a string."""
    return rx.process(text, mappings)


def assert_same(text: str, mappings: Mapping[str, str] | None = None) -> str:
    """Assert byte equality with the reference on ``text`` and return the output."""
    expected = reference_text(text, mappings)
    actual = ours_text(text, mappings)
    assert actual == expected
    return actual


def doc(body: str, root: str = "robot") -> str:
    """Wrap ``body`` in a root element declaring the xacro namespace."""
    return f'<{root} xmlns:xacro="http://www.ros.org/wiki/xacro">{body}</{root}>'
