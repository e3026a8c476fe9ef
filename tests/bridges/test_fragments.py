"""rosbridge's fragments, as data: splitting a text and joining it back in any order, rosbridge's
own float ``total``, and the refusals of what does not fit (a duplicate, a changed total, a
message whose last fragment is older than ``fragment_timeout_s``)."""

from __future__ import annotations

import json

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from robomodel.bridges import BridgeLimits
from robomodel.bridges.exceptions import ClientError
from robomodel.bridges.fragments import Reassembly, split


@settings(max_examples=50, deadline=None)
@given(st.text(min_size=1, max_size=400), st.integers(1, 300), st.randoms())
def test_split_then_joined_in_any_order_is_the_text(text: str, size: int, rng: object) -> None:
    fragments = [json.loads(f) for f in split(text, size, "m")]
    assert all(len(f["data"]) <= size and f["total"] == len(fragments) for f in fragments)
    rng.shuffle(fragments)  # type: ignore[attr-defined]
    joined = Reassembly(BridgeLimits(max_fragments=10_000))
    results = [joined.add(f) for f in fragments]
    assert results[:-1] == [None] * (len(fragments) - 1) and results[-1] == text
    assert joined.held_bytes == 0


def test_rosbridges_float_total_is_read_as_roslibjs_reads_it() -> None:
    joined = Reassembly(BridgeLimits())
    # rosbridge's Python 3 total for 5 characters in fragments of 2: (5 - 1) / 2 + 1
    assert joined.add({"id": 1, "num": 0, "total": 3.0, "data": "ab"}) is None
    assert joined.add({"id": 1, "num": 2, "total": 3.5, "data": "e"}) is None
    assert joined.add({"id": 1, "num": 1, "total": 3, "data": "cd"}) == "abcde"


def test_duplicates_changed_totals_and_stale_messages_are_refused() -> None:
    now = [0.0]
    joined = Reassembly(BridgeLimits(fragment_timeout_s=10.0), clock_s=lambda: now[0])
    joined.add({"id": "a", "num": 0, "total": 3, "data": "x"})
    with pytest.raises(ClientError, match="fragment a: fragment 0 came twice"):
        joined.add({"id": "a", "num": 0, "total": 3, "data": "x"})
    with pytest.raises(ClientError, match="total 4, where its first fragment said 3"):
        joined.add({"id": "a", "num": 1, "total": 4, "data": "y"})
    with pytest.raises(ClientError, match="'num' 3 is not in"):
        joined.add({"id": "a", "num": 3, "total": 3, "data": "y"})
    now[0] = 10.5  # past fragment_timeout_s: "a" is forgotten when the next fragment comes
    assert joined.add({"id": "b", "num": 0, "total": 2, "data": "q"}) is None
    assert joined.held_bytes == 1
    assert joined.add({"id": "a", "num": 1, "total": 2, "data": "z"}) is None  # a new "a"
