"""Every broken file gets urdfdom's verdict from ``robomodel check``, plus a location.

The reference is Debian's check_urdf (urdfdom 3.0.1) for URDF 1.0 and urdfdom 6.0 for the
1.1/1.2 rules. See broken_cases.py for what each verdict means.
"""

from __future__ import annotations

import re
import subprocess
from collections.abc import Callable
from pathlib import Path

import pytest

from tests.conftest import ToolResult
from tests.description.broken_cases import CASES, Case
from tests.timing import scaled

_LOC = re.compile(r"^(?P<path>.+?):(?P<line>\d+):(?P<col>\d+): (?P<sev>error|warning): ", re.M)


def _locations(text: str, severity: str) -> list[tuple[int, int]]:
    return [(int(m["line"]), int(m["col"])) for m in _LOC.finditer(text) if m["sev"] == severity]


def _assert_points_at(case: Case, found: list[tuple[int, int]]) -> None:
    assert found, f"{case.name}: no located diagnostic"
    line = case.line()
    if line is None:
        return
    lines = [loc[0] for loc in found]
    assert line in lines, f"{case.name}: expected line {line}, got {lines}"
    if case.at is not None and case.at.startswith("<"):
        text = case.xml.splitlines()[line - 1]
        column = text.index(case.at) + 1
        assert (line, column) in found, f"{case.name}: expected column {column}, got {found}"


@pytest.mark.parametrize("case", CASES, ids=[c.name for c in CASES])
def test_same_verdict_as_check_urdf(
    case: Case,
    tmp_path: Path,
    check_urdf: Callable[..., ToolResult],
    cli: Callable[..., ToolResult],
) -> None:
    path = tmp_path / f"{case.name}.urdf"
    path.write_text(case.xml)
    ours = cli("check", str(path))
    if case.verdict == "hang":
        with pytest.raises(subprocess.TimeoutExpired):
            check_urdf(path, timeout=scaled(3))
        assert ours.code == 0
        _assert_points_at(case, _locations(ours.out, "warning"))
        return
    ref = check_urdf(path, urdfdom6=case.urdfdom6)
    if case.verdict == "fatal":
        assert ref.code != 0, ref
        assert ours.code == 2
        _assert_points_at(case, _locations(ours.err, "error"))
        assert "Traceback" not in ours.err
    elif case.verdict == "error":
        assert ref.code == 0 and "Error:" in ref.err, ref
        assert ours.code == 2
        _assert_points_at(case, _locations(ours.err, "error"))
        assert ours.out.startswith(ref.out), "the tree is still printed, as check_urdf does"
    else:
        assert case.verdict == "warn"
        assert ref.code == 0 and "Error:" not in ref.err, ref
        assert ours.code == 0
        assert ours.out.startswith(ref.out)
        _assert_points_at(case, _locations(ours.out, "warning"))
        if case.code:
            strict = cli("check", "--json", str(path))
            assert f'"code": "{case.code}"' in strict.out


@pytest.mark.parametrize(
    "case", [c for c in CASES if c.verdict in ("warn", "hang")], ids=lambda c: c.name
)
def test_strict_turns_warnings_into_errors(
    case: Case, tmp_path: Path, cli: Callable[..., ToolResult]
) -> None:
    path = tmp_path / f"{case.name}.urdf"
    path.write_text(case.xml)
    result = cli("check", "--strict", str(path))
    assert result.code == 2
    assert _locations(result.err, "error")
