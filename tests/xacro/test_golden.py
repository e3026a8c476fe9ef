"""The reference's own byte-exact golden files (xacro 2.1.1 sdist, bazel integration test)."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from robomodel import xacro as rx

FIXTURES = Path(__file__).parent / "fixtures" / "bazel"

# (output name, input, mappings) as in the sdist's BUILD.bazel
GOLDEN = [
    ("sample1.xml", "inputs/sample1.xml.xacro", {}),
    ("sample2.xml", "inputs/sample2.xml.xacro", {}),
    ("my_complex_model.xml", "inputs/complex.xml.xacro", {"special_argument": "foo"}),
    ("conditional_default.xml", "inputs/conditional.xml.xacro", {}),
    ("conditional_false.xml", "inputs/conditional.xml.xacro", {"myarg": "false"}),
]


@pytest.fixture
def workdir(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    shutil.copytree(FIXTURES / "inputs", tmp_path / "inputs")
    monkeypatch.chdir(tmp_path)
    # complex.xml.xacro includes the generated outputs of two other targets
    for source, target in (
        ("inputs/sample1.xml.xacro", "inputs/sample1.xml"),
        ("inputs/deeply/nested/dependency.xml.xacro", "inputs/deeply/nested/dependency.xml"),
    ):
        Path(target).write_text(rx.process_file(source).toprettyxml(indent="  "))
    return tmp_path


@pytest.mark.parametrize(("expected", "source", "mappings"), GOLDEN, ids=[g[0] for g in GOLDEN])
def test_golden_file(workdir: Path, expected: str, source: str, mappings: dict[str, str]) -> None:
    output = rx.process_file(source, mappings).toprettyxml(indent="  ")
    assert output == (FIXTURES / "expected" / expected).read_text()
