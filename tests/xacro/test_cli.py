"""``robomodel xacro``: same output and exit codes as the reference CLI."""

from __future__ import annotations

from pathlib import Path

import pytest

from robomodel.cli.main import main
from tests.xacro.conftest import EXAMPLES, doc, reference_file


def _write(tmp_path: Path, body: str, name: str = "r.xacro") -> Path:
    path = tmp_path / name
    path.write_text(doc(body))
    return path


def test_stdout_matches_reference(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(tmp_path)
    _write(tmp_path, '<xacro:arg name="n" default="d"/><x v="$(arg n)"/>')
    assert main(["xacro", "r.xacro", "n:=given"]) == 0
    out = capsys.readouterr().out
    assert out == reference_file("r.xacro", {"n": "given"})
    assert 'v="given"' in out
    assert main(["xacro", "n:=first", "r.xacro"]) == 0
    assert 'v="first"' in capsys.readouterr().out


def test_package_options_resolve_find(capsys: pytest.CaptureFixture[str]) -> None:
    path = EXAMPLES / "rrbot_description/urdf/rrbot.xacro"
    assert main(["xacro", str(path), "--package", f"rrbot_description={path.parent.parent}"]) == 0
    assert '<link name="world"/>' in capsys.readouterr().out
    assert main(["xacro", str(path), "--package-path", str(EXAMPLES)]) == 0
    assert '<link name="world"/>' in capsys.readouterr().out


def test_output_file_is_written_atomically(tmp_path: Path) -> None:
    src = _write(tmp_path, "<x/>")
    out = tmp_path / "deep" / "dir" / "r.urdf"
    assert main(["xacro", str(src), "-o", str(out)]) == 0
    assert "<x/>" in out.read_text()
    assert [p.name for p in out.parent.iterdir()] == ["r.urdf"]


def test_error_leaves_no_output_and_exits_2(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    src = _write(tmp_path, '<x v="${undefined_thing}"/>')
    out = tmp_path / "r.urdf"
    assert main(["xacro", str(src), "-o", str(out)]) == 2
    assert not out.exists()
    err = capsys.readouterr().err
    assert err.startswith(f"{src}:1:") and "error: undefined name 'undefined_thing'" in err


def test_existing_output_survives_an_error(tmp_path: Path) -> None:
    src = _write(tmp_path, '<x v="${1/0}"/>')
    out = tmp_path / "r.urdf"
    out.write_text("old")
    assert main(["xacro", str(src), "-o", str(out)]) == 2
    assert out.read_text() == "old"


def test_deps(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    (tmp_path / "b.xacro").write_text(doc("<b/>"))
    (tmp_path / "a.xacro").write_text(doc("<a/>"))
    src = _write(tmp_path, '<xacro:include filename="b.xacro"/><xacro:include filename="a.xacro"/>')
    assert main(["xacro", "--deps", str(src)]) == 0
    assert capsys.readouterr().out == f"{tmp_path}/b.xacro {tmp_path}/a.xacro"


def test_inorder_accepted_and_quiet(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    src = _write(tmp_path, '<xacro:property name="pi" value="3"/><x/>')
    assert main(["xacro", "-i", str(src)]) == 0
    err = capsys.readouterr().err
    assert "in-order processing became default" in err and "redefining global symbol: pi" in err
    assert main(["xacro", "-q", str(src)]) == 0
    assert "redefining" not in capsys.readouterr().err


def test_private_mappings_are_dropped(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    src = _write(tmp_path, '<xacro:arg name="_p" default="d"/><x v="$(arg _p)"/>')
    assert main(["xacro", str(src), "_p:=cli"]) == 0
    assert 'v="d"' in capsys.readouterr().out


def test_two_inputs_are_refused(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    src = _write(tmp_path, "<x/>")
    assert main(["xacro", str(src), "other.xacro"]) == 2
    assert "exactly one input file" in capsys.readouterr().err


def test_missing_input(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["xacro", str(tmp_path / "nope.xacro")]) == 2
    assert "No such file" in capsys.readouterr().err


def test_unwritable_output_is_a_clean_error(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    src = _write(tmp_path, "<x/>")
    (tmp_path / "file").write_text("")
    assert main(["xacro", str(src), "-o", str(tmp_path / "file" / "out.urdf")]) == 2
    assert "cannot write" in capsys.readouterr().err
