"""Building blocks checked against the reference's own functions on generated inputs."""

from __future__ import annotations

import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

from robomodel.xacro._definitions import parse_macro_arg
from robomodel.xacro._lexer import LexError, TokenKind, tokenize_text
from robomodel.xacro._symbols import BooleanError, eval_literal, is_valid_name, to_boolean

xacro = pytest.importorskip("xacro")

LITERALS = st.one_of(
    st.text(max_size=8),
    st.sampled_from(["1", " 2 ", "1.5", "1e3", "inf", "nan", "true", "False", "'q'", "1_0", "0x1"]),
)


@settings(max_examples=500)
@given(LITERALS)
def test_eval_literal_matches_reference(value: str) -> None:
    assert repr(eval_literal(value)) == repr(xacro.Table._eval_literal(value))


@settings(max_examples=300)
@given(st.one_of(LITERALS, st.integers(), st.floats(allow_nan=False), st.lists(st.integers())))
def test_to_boolean_matches_reference(value: object) -> None:
    try:
        expected = xacro.get_boolean_value(value, "c")
    except xacro.XacroException:
        with pytest.raises(BooleanError):
            to_boolean(value, "c")
        return
    assert to_boolean(value, "c") == expected


@settings(max_examples=300)
@given(st.text(alphabet="ab_1 .-:é", max_size=6))
def test_is_valid_name_matches_reference(name: str) -> None:
    assert is_valid_name(name) == xacro.is_valid_name(name)


PARAMS = st.lists(
    st.sampled_from(
        [
            "a",
            "b:=1",
            "c=2",
            "d:=^",
            "e:=^|3",
            "*f",
            "**g",
            "h:='x y'",
            'i:="q"',
            "j:=${1+2}",
            "k:=$(arg x)",
            "l:=a'b'c",
        ]
    ),
    min_size=1,
    max_size=4,
).map(" ".join)


@settings(max_examples=300)
@given(PARAMS)
def test_parse_macro_arg_matches_reference(params: str) -> None:
    assert parse_macro_arg(params) == xacro.parse_macro_arg(params)


def _reference_tokens(text: str) -> list[tuple[TokenKind, str]]:
    lexer = xacro.QuickLexer(xacro.LEXER)
    lexer.lex(text)
    kinds = {lexer.EXPR: TokenKind.EXPR, lexer.EXTENSION: TokenKind.EXTENSION}
    tokens = []
    while lexer.peek():
        kind, value = lexer.next()
        if kind == lexer.DOLLAR_DOLLAR_BRACE:
            tokens.append((TokenKind.TEXT, value[1:]))
        elif kind in kinds:
            tokens.append((kinds[kind], value[2:-1]))
        else:
            tokens.append((TokenKind.TEXT, value))
    return tokens


@settings(max_examples=500)
@given(st.text(alphabet="$${}()ab '", max_size=12))
@example("${{}$(}")  # found by a CI run: the reference fails where robomodel nests
def test_lexer_matches_reference_without_nesting(text: str) -> None:
    try:
        expected = _reference_tokens(text)
    except xacro.XacroException:
        try:
            ours = list(tokenize_text(text))
        except LexError:
            return
        # robomodel matches braces in balance ('${{}$(}' is one expression, '{}$('), where
        # the reference's regex stops at the first '}' and then fails on the rest: nesting
        assert any(k is not TokenKind.TEXT and ("{" in v or "(" in v) for k, v in ours), ours
        return
    nested = any(
        k is not TokenKind.TEXT and ("{" in v or "(" in v or "'" in v) for k, v in expected
    )
    if not nested:  # balanced matching only differs where the reference splits inside
        assert list(tokenize_text(text)) == expected
