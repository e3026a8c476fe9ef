"""The reference's known bugs (reference notes, "Quirks to fix"): our fixed behaviour, and the
reference's failure that makes these constructs excluded from byte comparisons."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from robomodel import xacro as rx
from robomodel.errors import InputError
from tests.xacro.conftest import doc, reference_text


def _reference_fails(text: str) -> None:
    with pytest.raises(Exception):  # noqa: B017 - any failure of the reference
        reference_text(text)


def test_dirname_is_the_directory_of_the_current_file(tmp_path: Path) -> None:
    sub = tmp_path / "sub"
    sub.mkdir()
    (sub / "inc.xacro").write_text(doc('<i d="$(dirname)"/>'))
    main = tmp_path / "main.xacro"
    main.write_text(doc('<m d="$(dirname)"/><xacro:include filename="sub/inc.xacro"/>'))
    out = rx.process_file(main).toprettyxml(indent="  ")
    assert f'<m d="{tmp_path}"/>' in out
    assert f'<i d="{sub}"/>' in out


def test_eval_with_parentheses() -> None:
    text = doc('<x v="$(eval int(floor(2.7)) + 1)"/>')
    _reference_fails(text)
    assert 'v="3"' in rx.process(text)


def test_nested_expressions() -> None:
    text = doc(
        '<xacro:property name="b" value="4"/><x v="${1 + ${b}}" w="${ {\'k\': 5}[\'k\'] }"/>'
    )
    _reference_fails(text)
    out = rx.process(text)
    assert 'v="5"' in out and 'w="5"' in out


def test_attribute_with_non_string_value() -> None:
    text = doc('<x><xacro:attribute name="n" value="${1+1}"/></x>')
    _reference_fails(text)
    assert '<x n="2"/>' in rx.process(text)


def test_scope_parent_at_top_level_warns_instead_of_crashing(tmp_path: Path) -> None:
    text = doc('<xacro:property name="p" value="1" scope="parent"/><x/>')
    _reference_fails(text)
    path = tmp_path / "p.xacro"
    path.write_text(text)
    result = rx.process_file(path)
    assert any("no parent scope" in w.message for w in result.warnings)
    assert "<x/>" in result.toprettyxml()


def test_substitution_errors_are_not_doubled() -> None:
    with pytest.raises(InputError) as info:
        rx.process(doc('<x v="$(env ROBOMODEL_SURELY_UNSET_VAR)"/>'))
    assert info.value.message.count("ROBOMODEL_SURELY_UNSET_VAR") <= 2
    assert "<class" not in info.value.message


def test_deps_are_ordered_and_unique(tmp_path: Path) -> None:
    for name in ("z", "a", "m"):
        (tmp_path / f"{name}.xacro").write_text(doc(f"<{name}/>"))
    (tmp_path / "c.yaml").write_text("k: 1\n")
    main = tmp_path / "main.xacro"
    main.write_text(
        doc(
            '<xacro:include filename="z.xacro"/><xacro:include filename="a.xacro"/>'
            '<x v="${xacro.load_yaml(\'c.yaml\').k}"/><xacro:include filename="m.xacro"/>'
            '<xacro:include filename="a.xacro"/>'
        )
    )
    result = rx.expand(main)
    assert [os.path.basename(p) for p in result.includes] == [
        "z.xacro",
        "a.xacro",
        "c.yaml",
        "m.xacro",
    ]


def test_arg_defaults_do_not_leak_between_calls(tmp_path: Path) -> None:
    first, second = tmp_path / "f1.xacro", tmp_path / "f2.xacro"
    first.write_text(doc('<xacro:arg name="foo" default="1"/><x v="$(arg foo)"/>'))
    second.write_text(doc('<xacro:arg name="foo" default="2"/><x v="$(arg foo)"/>'))
    assert 'v="1"' in rx.process(str(first))
    assert 'v="2"' in rx.process(str(second))
    mappings: dict[str, str] = {}
    rx.process_file(first, mappings)
    assert mappings == {}
