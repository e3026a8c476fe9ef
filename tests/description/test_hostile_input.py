"""Hostile and degenerate input: one located diagnostic, exit 2, no traceback, nothing written."""

from __future__ import annotations

import time
from collections.abc import Callable
from pathlib import Path

import pytest

from robomodel.description import read_urdf
from robomodel.errors import InputError
from tests.conftest import ToolResult

BILLION_LAUGHS = """<?xml version="1.0"?>
<!DOCTYPE robot [
 <!ENTITY lol "lol">
 <!ENTITY lol2 "&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;">
 <!ENTITY lol3 "&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;">
 <!ENTITY lol4 "&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;">
 <!ENTITY lol5 "&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;">
 <!ENTITY lol6 "&lol5;&lol5;&lol5;&lol5;&lol5;&lol5;&lol5;&lol5;&lol5;&lol5;">
 <!ENTITY lol7 "&lol6;&lol6;&lol6;&lol6;&lol6;&lol6;&lol6;&lol6;&lol6;&lol6;">
 <!ENTITY lol8 "&lol7;&lol7;&lol7;&lol7;&lol7;&lol7;&lol7;&lol7;&lol7;&lol7;">
 <!ENTITY lol9 "&lol8;&lol8;&lol8;&lol8;&lol8;&lol8;&lol8;&lol8;&lol8;&lol8;">
]>
<robot name="&lol9;"><link name="a"/></robot>
"""

XXE = """<?xml version="1.0"?>
<!DOCTYPE robot [ <!ENTITY secret SYSTEM "file:///etc/passwd"> ]>
<robot name="r"><link name="&secret;"/></robot>
"""


def _check(cli: Callable[..., ToolResult], path: Path) -> ToolResult:
    result = cli("check", str(path))
    assert result.code == 2
    assert "Traceback" not in result.err
    lines = [line for line in result.err.splitlines() if line]
    assert len(lines) == 1, result.err
    assert lines[0].startswith(f"{path}:")
    return result


def test_billion_laughs_refused_quickly(tmp_path: Path, cli: Callable[..., ToolResult]) -> None:
    path = tmp_path / "bomb.urdf"
    path.write_text(BILLION_LAUGHS)
    start = time.perf_counter()
    result = _check(cli, path)
    assert time.perf_counter() - start < 2.0
    assert "entity declarations are not allowed" in result.err
    assert f"{path}:3:2: error" in result.err


def test_external_entity_refused(tmp_path: Path, cli: Callable[..., ToolResult]) -> None:
    path = tmp_path / "xxe.urdf"
    path.write_text(XXE)
    result = _check(cli, path)
    assert "root:" not in result.err and "root:" not in result.out  # /etc/passwd never read
    assert "<!ENTITY secret" in result.err


def test_huge_file_refused_without_reading(tmp_path: Path, cli: Callable[..., ToolResult]) -> None:
    path = tmp_path / "huge.urdf"
    with path.open("wb") as handle:
        handle.write(b'<robot name="r"><link name="a"/>')
        handle.seek(50 * 1024 * 1024)
        handle.write(b"</robot>")
    result = _check(cli, path)
    assert "MB" in result.err and "limit" in result.err


@pytest.mark.parametrize(
    ("name", "text", "needle"),
    [
        ("empty", "", "empty"),
        ("blank", "   \n\n", "empty"),
        ("malformed", '<robot name="r"><link name="a"></robot>', "malformed XML"),
        ("not_xml", "hello world", "malformed XML"),
        ("binary", "\x00\x01\x02", "malformed XML"),
        (
            "nan_origin",
            '<robot name="r"><link name="a"/><link name="b"/><joint name="j" type="fixed"><origin xyz="nan 0 0"/><parent link="a"/><child link="b"/></joint></robot>',
            "nan",
        ),
        (
            "missing_attr",
            '<robot name="r"><link name="a"/><link name="b"/><joint name="j"><parent link="a"/><child link="b"/></joint></robot>',
            "has no type",
        ),
    ],
)
def test_bad_input_one_clear_line(
    name: str, text: str, needle: str, tmp_path: Path, cli: Callable[..., ToolResult]
) -> None:
    path = tmp_path / f"{name}.urdf"
    path.write_text(text)
    result = _check(cli, path)
    assert needle in result.err


def test_missing_file(cli: Callable[..., ToolResult], tmp_path: Path) -> None:
    result = cli("check", str(tmp_path / "nope.urdf"))
    assert result.code == 2 and "cannot read" in result.err and "Traceback" not in result.err


def test_debug_shows_traceback(tmp_path: Path) -> None:
    from robomodel.cli.main import main

    path = tmp_path / "bad.urdf"
    path.write_text("<robot>")
    with pytest.raises(InputError):
        main(["--debug", "check", str(path)])


def test_string_input_refused_the_same_way() -> None:
    with pytest.raises(InputError) as info:
        read_urdf(BILLION_LAUGHS, path="<bomb>")
    assert info.value.path == "<bomb>"


def test_graph_output_not_written_on_error(tmp_path: Path, cli: Callable[..., ToolResult]) -> None:
    bad = tmp_path / "bad.urdf"
    bad.write_text('<robot name="r"><link name="a"/><link name="b"/></robot>')  # two roots
    out = tmp_path / "out.svg"
    result = cli("graph", str(bad), "-o", str(out))
    assert result.code == 2 and not out.exists()
    assert list(tmp_path.iterdir()) == [bad]
