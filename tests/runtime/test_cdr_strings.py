"""CDR strings: the generated codecs code a ``string`` field inline (its length packed with
the fixed-size values before it) and a ``string[]`` through a memo (a repeated list is coded
from the memo). What goes on the wire or comes out of a decoder is the same as without them:
bytes checked against pycdr2, an independent implementation.

No ``from __future__ import annotations`` here: pycdr2 reads the real annotation objects.
"""

import dataclasses

import pycdr2
import pytest
from hypothesis import given
from hypothesis import strategies as st
from pycdr2.types import array, sequence, uint8

from robomodel.runtime import msg as m
from robomodel.runtime.msg import _cdr_strings


@dataclasses.dataclass(slots=True)
class Named(m.Message):
    """string[] after a byte (its count needs padding), a string[2] and a second string[]."""

    flag: int = 0
    names: list = dataclasses.field(default_factory=list)
    pair: list = dataclasses.field(default_factory=lambda: ["", ""])
    tail: list = dataclasses.field(default_factory=list)
    __typename__ = "robomodel_test/msg/Named"
    __fields__ = (
        ("flag", "uint8"),
        ("names", m.Seq("string")),
        ("pair", m.Array("string", 2)),
        ("tail", m.Seq("string")),
    )


@dataclasses.dataclass
class RefNamed(pycdr2.IdlStruct, typename="robomodel_test/msg/Named"):
    flag: uint8
    names: sequence[str]
    pair: array[str, 2]
    tail: sequence[str]


words = st.text(alphabet=st.characters(min_codepoint=32, max_codepoint=0x2FF), max_size=9)
lists = st.lists(words, max_size=5)


@given(st.lists(st.tuples(st.integers(0, 255), lists, st.tuples(words, words), lists), max_size=6))
def test_a_run_of_messages_matches_pycdr2_message_by_message(runs) -> None:  # type: ignore[no-untyped-def]
    # hypothesis repeats lists and prefixes of lists: hits and misses of the memo alike
    for flag, names, pair, tail in [*runs, *runs]:
        ours = Named(flag, names, list(pair), tail)
        payload = m.serialize(ours)
        assert payload == RefNamed(flag, names, list(pair), tail).serialize()
        assert m.deserialize(payload, Named) == ours


def test_a_list_changed_in_place_is_encoded_anew() -> None:
    names = ["shoulder", "elbow"]
    msg = Named(1, names)
    first = m.serialize(msg)
    names[1] = "wrist"
    assert m.serialize(msg) == RefNamed(1, ["shoulder", "wrist"], ["", ""], []).serialize()
    names[1] = "elbow"
    assert m.serialize(msg) == first


def test_each_decode_returns_a_new_list() -> None:
    payload = m.serialize(Named(0, ["a", "b"]))
    first = m.deserialize(payload, Named)
    first.names.append("mine")
    again = m.deserialize(payload, Named)
    assert again.names == ["a", "b"]
    assert again.names is not first.names


@pytest.mark.parametrize(
    ("before", "after"),
    [
        (["joint_a", "joint_b"], ["joint_a", "joint_bc"]),  # same prefix, longer last string
        (["joint_a", "joint_b"], ["joint_a", "joint_b", "joint_c"]),  # one more
        (["joint_a", "joint_b"], ["joint_a"]),  # one fewer: the old bytes are still a prefix
        (["é", "b"], ["e", "b"]),  # same length, other bytes
    ],
)
def test_a_different_list_after_a_remembered_one_decodes_as_sent(before, after) -> None:  # type: ignore[no-untyped-def]
    for names in (before, after, before):
        payload = RefNamed(3, names, ["x", "y"], names).serialize()
        assert m.deserialize(payload, Named) == Named(3, names, ["x", "y"], names)


def test_a_truncated_repeat_is_still_refused() -> None:
    payload = m.serialize(Named(0, ["left", "right"]))
    m.deserialize(payload, Named)  # remembered
    with pytest.raises(m.CDRError):
        m.deserialize(payload[:20], Named)


def test_large_lists_are_not_remembered() -> None:
    memo = _cdr_strings.StringsMemo()
    big = ["x" * 1000] * (_cdr_strings.MEMO_MAX_BYTES // 1000 + 1)
    buf = bytearray(b"\x00\x01\x00\x00")
    memo.encode(buf, big)
    assert memo._encoded is None
    items, end = memo.decode(bytes(buf), 8, len(big))
    assert items == big and end == len(buf)
    assert memo._decoded is None
    small = ["a", "b"]
    memo.encode(bytearray(b"\x00\x01\x00\x00"), small)
    assert memo._encoded is not None and memo._encoded[0] == ("a", "b")


def test_strings_decoded_inline_refuse_bad_bytes_with_a_cdr_error() -> None:
    good = m.serialize(m.String("abc"))  # header, uint32 4, "abc\0"
    assert m.deserialize(good, m.String) == m.String("abc")
    with pytest.raises(m.CDRError, match="UTF-8"):
        m.deserialize(good[:8] + b"\xff\xfe\xfd\x00", m.String)
    with pytest.raises(m.CDRError, match="truncated"):
        m.deserialize(good[:-1], m.String)
    with pytest.raises(m.CDRError, match="truncated"):
        m.deserialize(good[:6], m.String)
    # a length of 0 (no NUL) is read as the empty string, as before
    assert m.deserialize(b"\x00\x01\x00\x00" + b"\x00" * 4, m.String) == m.String("")
    named = m.serialize(Named(1, ["é"]))
    with pytest.raises(m.CDRError, match="UTF-8"):
        m.deserialize(named.replace("é".encode(), b"\xff\xfe"), Named)
