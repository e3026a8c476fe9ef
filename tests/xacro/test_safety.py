"""Escape attempts and runaway inputs: each must be refused quickly with a clear error."""

from __future__ import annotations

import time
from pathlib import Path

import pytest

from robomodel import xacro as rx
from robomodel.errors import InputError, RobomodelError
from tests.xacro.conftest import doc, reference_text

ESCAPES = [
    "().__class__",
    "[x.__class__ for x in [1]]",
    "(lambda: ().__class__.__bases__[0].__subclasses__())()",
    "(lambda f: f.__globals__)(lambda: 0)",
    "{k: v for k, v in [(1, ().__class__)]}",
    "[y for x in [1] for y in [x.__class__.__mro__]]",
    "'{0.__class__}'.format(1)",
    "'{0.real}'.format(1)",
    "'{a.__class__}'.format_map(dict(a=1))",
    "f'{().__class__}'",
    "getattr(1, '__class__')",
    "__import__('os')",
    "_rm_attr(1, '__class__')",
    "python.vars(python.type(1))",
    "python.type('X', (), {})",
    "python.type(1).mro()",
    "python.type(python.type(1))('X', (), {})",
    "str.format('{0.__class__}', 1)",
    "xacro.load_yaml.__globals__",
    "math.__dict__",
    "(x for x in []).gi_frame",
    "(lambda: 0).__code__",
    "xacro.arg.something",
    "dict(a=1).items().mapping",
    "python.isinstance.__self__",
    "lambda __x: 0",
    "[__x for __x in [1]]",
    "dict(__class__=1)",
    "(a := 1)",
]

RUNAWAY = [
    "10**10**10",
    "2**100000000",
    "'a'*10**9",
    "[0]*10**9",
    "1 << 10**9",
    "'a'.ljust(10**10)",
    "'%999999999s' % 1",
    "f'{1:999999999}'",
    "python.range(10**12)",
    "[1 for x in python.range(10**6) for y in python.range(10**6)]",
    "math.factorial(10**7)",
    "(lambda f: f(f))(lambda f: f(f))",
    "'-'.join(['x' * 10**6] * 10**6)",
]


def _attr(expr: str) -> str:
    for char, entity in (("&", "&amp;"), ("<", "&lt;"), ("'", "&apos;"), ('"', "&quot;")):
        expr = expr.replace(char, entity)
    return expr


@pytest.mark.parametrize("expr", ESCAPES)
def test_escape_is_refused(expr: str) -> None:
    with pytest.raises(InputError) as info:
        rx.process(doc(f'<x v="${{{_attr(expr)}}}"/>'))
    message = info.value.message
    assert "not allowed" in message or "undefined name" in message or "Error" in message
    assert info.value.line == 1


@pytest.mark.parametrize("expr", RUNAWAY)
def test_runaway_expression_is_bounded(expr: str) -> None:
    start = time.perf_counter()
    with pytest.raises(InputError) as info:
        rx.process(doc(f'<x v="${{{_attr(expr)}}}"/>'))
    assert time.perf_counter() - start < 10
    assert any(
        word in info.value.message
        for word in ("too large", "longer than", "loops more", "recursion", "larger than")
    ), info.value.message


def test_reference_is_escapable_but_we_are_not() -> None:
    # The reference checks only the top-level code object (xacro/__init__.py L239).
    body = '<x v="${[x.__class__.__name__ for x in [1]]}"/>'
    assert "[&apos;int&apos;]" in reference_text(doc(body)) or "['int']" in reference_text(
        doc(body)
    )
    with pytest.raises(InputError, match="not allowed"):
        rx.process(doc(body))


def test_eval_extension_is_bounded_too() -> None:
    with pytest.raises(InputError, match="larger than"):
        rx.process(doc('<x v="$(eval factorial(10**7))"/>'))


def test_infinite_macro_recursion_is_bounded() -> None:
    with pytest.raises(InputError, match="nested deeper"):
        rx.process(doc('<xacro:macro name="r"><xacro:r/></xacro:macro><xacro:r/>'))


def test_exponential_block_growth_is_bounded() -> None:
    body = (
        '<xacro:macro name="d" params="n **b"><xacro:if value="${n}">'
        '<xacro:d n="${n-1}"><w><xacro:insert_block name="b"/><xacro:insert_block name="b"/></w>'
        "</xacro:d>"
        '</xacro:if><xacro:unless value="${n}"><xacro:insert_block name="b"/></xacro:unless></xacro:macro>'
        '<xacro:d n="40"><w><x/></w></xacro:d>'
    )
    start = time.perf_counter()
    with pytest.raises(InputError, match="more than"):
        rx.process(doc(body), limits=rx.Limits(max_nodes=200_000))
    assert time.perf_counter() - start < 20


def test_string_doubling_through_properties_is_bounded() -> None:
    props = '<xacro:property name="p0" value="${\'x\' * 1000}"/>' + "".join(
        f'<xacro:property name="p{i}" value="${{p{i - 1} + p{i - 1}}}"/>' for i in range(1, 40)
    )
    with pytest.raises(InputError, match="longer than"):
        rx.process(doc(props + '<x v="${p39}"/>'))


def test_entity_declarations_are_refused() -> None:
    bomb = '<?xml version="1.0"?><!DOCTYPE r [<!ENTITY a "aaaa"><!ENTITY b "&a;&a;">]><r>&b;</r>'
    with pytest.raises(InputError, match="DOCTYPE"):
        rx.process(bomb)


def test_whitelist_keeps_what_real_files_use() -> None:
    body = (
        "<x a=\"${[i for i in range(3) if i % 2 == 0]}\" b=\"${ {'k': 1}['k'] }\" "
        'c="${(lambda v: v * 2)(3)}" d="${\'ab\'[::-1]}" e="${1 if True else 2}" '
        'f="${sorted({3, 1})}" g="${\'%.2f\' % 0.5}" h="${f\'{2:03d}\'}" '
        'i="${\'{}-{}\'.format(1, 2)}" j="${dict(a=1).get(\'a\')}" k="${(1).real}" '
        'l="${not (1 &lt; 2 &lt;= 3)}" m="${-2**2}"/>'
    )
    out = rx.process(doc(body))
    for expected in ('a="[0, 2]"', 'b="1"', 'c="6"', 'd="ba"', 'e="1"', 'f="[1, 3]"', 'g="0.50"',
                     'h="002"', 'i="1-2"', 'j="1"', 'k="1"', 'l="False"', 'm="-4"'):  # fmt: skip
        assert expected in out


def test_output_size_is_bounded() -> None:
    body = '<xacro:property name="s" value="${\'x\' * 5000}"/>' + '<a v="${s}"/>' * 50
    with pytest.raises(RobomodelError, match="output larger than"):
        rx.process(doc(body), limits=rx.Limits(max_output_chars=100_000))
    assert len(rx.process(doc(body))) > 250_000


def test_deep_nesting_is_a_clean_error() -> None:
    text = doc("<a>" * 5000 + "</a>" * 5000)
    with pytest.raises(InputError, match="nested too deeply"):
        rx.process(text)


def test_self_including_file_is_bounded(tmp_path: Path) -> None:
    path = tmp_path / "self.xacro"
    path.write_text(doc('<xacro:include filename="self.xacro"/>'))
    with pytest.raises(InputError, match="does a file include itself"):
        rx.process_file(path)
