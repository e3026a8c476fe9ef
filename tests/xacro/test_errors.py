"""Errors: ``file:line:column: error: message`` plus the include and macro stack."""

from __future__ import annotations

from pathlib import Path

import pytest

from robomodel import xacro as rx
from robomodel.errors import InputError, Severity

HEAD = '<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n'


def _error(text: str, tmp_path: Path, name: str = "robot.xacro") -> InputError:
    path = tmp_path / name
    path.write_text(text)
    with pytest.raises(InputError) as info:
        rx.process_file(path)
    return info.value


def test_undefined_name_has_line_column_and_close_matches(tmp_path: Path) -> None:
    err = _error(
        HEAD + '<xacro:property name="width" value="1"/>\n  <box size="${widht}"/>\n</robot>',
        tmp_path,
    )
    assert (err.line, err.column) == (3, 14)  # the "${" of the expression
    assert err.path is not None and err.path.endswith("robot.xacro")
    assert "undefined name 'widht'" in err.message and "did you mean 'width'" in err.message


def test_macro_stack_frames(tmp_path: Path) -> None:
    text = (
        HEAD
        + '<xacro:macro name="wheel" params="side">\n'  # line 2
        + '  <link name="${sid}_wheel"/>\n'  # line 3
        + "</xacro:macro>\n"
        + '<xacro:macro name="base">\n'  # line 5
        + '  <xacro:wheel side="left"/>\n'  # line 6
        + "</xacro:macro>\n"
        + "<xacro:base/>\n"  # line 8
        + "</robot>\n"
    )
    err = _error(text, tmp_path, "simplebot.urdf.xacro")
    assert (err.line, err.column) == (3, 15)
    assert [n.severity for n in err.notes] == [Severity.NOTE, Severity.NOTE]
    assert err.notes[0].message == (
        "in macro 'wheel' (simplebot.urdf.xacro:2), called from simplebot.urdf.xacro:6"
    )
    assert err.notes[1].message == (
        "in macro 'base' (simplebot.urdf.xacro:5), called from simplebot.urdf.xacro:8"
    )
    assert err.notes[0].location.line == 6


def test_include_frame_and_error_in_included_file(tmp_path: Path) -> None:
    (tmp_path / "inc.xacro").write_text(HEAD + '\n<x v="${nope}"/>\n</robot>')
    err = _error(HEAD + '<xacro:include filename="inc.xacro"/>\n</robot>', tmp_path)
    assert err.path is not None and err.path.endswith("inc.xacro")
    assert err.line == 3
    assert "in file" in err.notes[0].message and "robot.xacro:2" in err.notes[0].message


def test_xml_error_is_located_with_hint(tmp_path: Path) -> None:
    err = _error("<robot>\n  <xacro:foo/>\n</robot>", tmp_path)
    assert "unbound prefix" in err.message and err.line == 2
    assert "xmlns:xacro" in err.notes[0].message


def test_malformed_included_file_names_that_file(tmp_path: Path) -> None:
    (tmp_path / "bad.xacro").write_text("<robot>\n<a></b>\n</robot>")
    err = _error(HEAD + '<xacro:include filename="bad.xacro"/>\n</robot>', tmp_path)
    assert err.path is not None and err.path.endswith("bad.xacro") and err.line == 2


@pytest.mark.parametrize(
    ("body", "fragment"),
    [
        ("<xacro:foo/>", "unknown macro name: xacro:foo"),
        ('<xacro:macro name="m" params="a"/><xacro:m b="1"/>', 'Invalid parameter "b"'),
        ('<xacro:macro name="m" params="a"/><xacro:m/>', "Undefined parameters [a]"),
        ('<xacro:macro name="m" params="*b"/><xacro:m/>', "Not enough blocks"),
        ('<xacro:macro name="m"/><xacro:m><x/></xacro:m>', 'Unused block "x"'),
        ('<xacro:macro name="m" params="a:=^"/><xacro:m/>', "Undefined property to forward: a"),
        ('<xacro:insert_block name="q"/>', 'Undefined block "q"'),
        ('<xacro:if value="1.0"/>', "not a boolean expression"),
        ('<xacro:property name="a b" value="1"/>', "valid Python identifiers"),
        ('<xacro:property name="__a" value="1"/>', "double underscore"),
        ('<xacro:property name="a" value="1" default="2"/>', "mutually exclusive"),
        ('<xacro:macro name="a.b"/>', "must not contain '.'"),
        ('<xacro:macro name="call"/>', "reserved"),
        ('<xacro:arg name="a"/>', "missing attribute 'default'"),
        ('<x v="$(arg undefined_arg)"/>', "undefined substitution argument 'undefined_arg'"),
        ('<x v="$(foo bar)"/>', "unknown substitution command"),
        ('<x v="$(env ROBOMODEL_SURELY_UNSET)"/>', "is not set"),
        ('<xacro:include filename="missing.xacro"/>', "No such file"),
        (
            '<xacro:property name="a" value="${b}"/><xacro:property name="b" value="${a}"/><x v="${a}"/>',
            "circular variable definition",
        ),
        ('<x v="${1/0}"/>', "ZeroDivisionError"),
        ("<x v=\"${xacro.fatal('stop here')}\"/>", "stop here"),
        ('<x v="$$x"/>', "invalid expression"),
        ('<xacro:element xacro:name=""/>', "empty name"),
    ],
)
def test_error_messages(body: str, fragment: str, tmp_path: Path) -> None:
    err = _error(HEAD + body + "\n</robot>", tmp_path)
    assert fragment in err.message
    assert err.line is not None and err.line >= 1
    assert err.message.count(fragment) == 1  # never doubled


def test_warnings_are_returned(tmp_path: Path) -> None:
    path = tmp_path / "w.xacro"
    path.write_text(
        HEAD
        + '<xacro:property name="pi" value="3"/><xacro:property name="a" value="1" bogus="2"/>\n</robot>'
    )
    doc = rx.process_file(path)
    messages = [w.message for w in doc.warnings]
    assert any("redefining global symbol: pi" in m for m in messages)
    assert any("unknown attribute(s): bogus" in m for m in messages)
