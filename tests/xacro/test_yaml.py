"""``xacro.load_yaml``: unit tags, dotted access, wrapping, paths relative to the current file."""

from __future__ import annotations

from pathlib import Path

import pytest

from robomodel import xacro as rx
from robomodel.errors import InputError
from tests.xacro.conftest import doc, reference_file

YAML = """\
arm:
  length: !meters 0.5
  offset: !millimeters 25
  lift: !foot 1
  pad: !inches 2
  limit: !degrees 2*90
  twist: !radians pi/4
  joints:
    - {name: j1, port: 7}
    - {name: j2, port: 8}
name: "bot"
items: [1, 2.5, "x"]
"""


@pytest.fixture
def package(tmp_path: Path) -> Path:
    (tmp_path / "config").mkdir()
    (tmp_path / "config" / "p.yaml").write_text(YAML)
    (tmp_path / "urdf").mkdir()
    return tmp_path / "urdf"


def test_units_and_dotted_access_match_reference(package: Path) -> None:
    path = package / "r.xacro"
    path.write_text(
        doc(
            '<xacro:property name="p" value="${xacro.load_yaml(\'../config/p.yaml\')}"/>'
            '<u l="${p.arm.length}" o="${p.arm.offset}" f="${p.arm.lift}" i="${p.arm.pad}"'
            ' d="${p.arm.limit}" r="${p.arm.twist}"/>'
            '<j n="${p.arm.joints[1].name}" k="${[j.port for j in p.arm.joints]}" s="${p[\'name\']}"/>'
            "<l v=\"${p['items']}\" n=\"${len(p['items'])}\" h=\"${'arm' in p}\"/>"
        )
    )
    output = rx.process_file(path).toprettyxml(indent="  ")
    assert output == reference_file(path)
    for expected in ('l="0.5"', 'o="0.025"', 'f="0.3048"', 'i="0.0508"', 'd="3.141592653589793"',
                     'r="0.7853981633974483"', 'n="j2"', 'k="[7, 8]"', 's="bot"'):  # fmt: skip
        assert expected in output
    assert rx.process_file(path).includes[0].endswith("p.yaml")


def test_missing_key_is_an_error(package: Path) -> None:
    path = package / "r.xacro"
    path.write_text(doc("<x v=\"${xacro.load_yaml('../config/p.yaml').arm.lenght}\"/>"))
    with pytest.raises(InputError, match="no key 'lenght'"):
        rx.process_file(path)


def test_missing_file_is_an_error(package: Path) -> None:
    path = package / "r.xacro"
    path.write_text(doc("<x v=\"${xacro.load_yaml('nope.yaml')}\"/>"))
    with pytest.raises(InputError, match="cannot read YAML file"):
        rx.process_file(path)


def test_bad_unit_expression(package: Path) -> None:
    (package / "bad.yaml").write_text("a: !degrees 2*\n")
    path = package / "r.xacro"
    path.write_text(doc("<x v=\"${xacro.load_yaml('bad.yaml').a}\"/>"))
    with pytest.raises(InputError, match="invalid expression in YAML unit value"):
        rx.process_file(path)
