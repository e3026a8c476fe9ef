"""float64[] fields: coded through array('d') on little-endian hosts, with
the bytes that struct's explicit little-endian format gives, for every value a list, tuple or
numpy array of numbers can hold; anything else is refused as it was."""

from __future__ import annotations

import math
import struct

import numpy as np
import pytest

from robomodel.runtime import msg as m
from robomodel.runtime.msg.cdr import CDRError, deserialize, payload_decoder, serialize

SPECIAL = [0.0, -0.0, 1.5, -2.25e-308, 1.7976931348623157e308, math.inf, -math.inf, 5e-324]


def _reference(values: list[float]) -> bytes:
    """The JointState's bytes by hand: header, stamp, frame "", no names, positions."""
    head = b"\x00\x01\x00\x00" + struct.pack("<iII", 7, 8, 1) + b"\x00"
    head += b"\x00" * (-(len(head) - 4) % 4) + struct.pack("<I", 0)  # name: string[] of 0
    head += struct.pack("<I", len(values))
    if values:
        head += b"\x00" * (-(len(head) - 4) % 8) + struct.pack(f"<{len(values)}d", *values)
    return head + struct.pack("<II", 0, 0)  # velocity, effort: empty


@pytest.mark.parametrize(
    "values",
    [SPECIAL, tuple(SPECIAL), np.array(SPECIAL), [1, 2, True], np.arange(3, dtype=np.float32)],
    ids=["list", "tuple", "numpy", "ints and a bool", "float32 numpy"],
)
def test_float64_sequences_code_as_struct_does(values: object) -> None:
    msg = m.JointState(m.Header(m.Time(7, 8), ""), [], values)  # type: ignore[arg-type]
    expected = [float(v) for v in values]  # type: ignore[attr-defined]
    assert serialize(msg) == _reference(expected)
    back = deserialize(serialize(msg), m.JointState)
    assert back.position == expected
    assert [math.copysign(1, v) for v in back.position] == [math.copysign(1, v) for v in expected]


def test_nan_survives_the_round_trip() -> None:
    msg = m.JointState(position=[math.nan, 1.0])
    assert math.isnan(deserialize(serialize(msg), m.JointState).position[0])


@pytest.mark.parametrize("bad", [["x"], [None], [1.0, object()], [10**400]])
def test_a_value_that_is_not_a_float64_is_refused(bad: list[object]) -> None:
    with pytest.raises(CDRError, match="JointState: a value does not fit its field"):
        serialize(m.JointState(position=bad))  # type: ignore[arg-type]


def test_a_truncated_float64_sequence_is_refused() -> None:
    data = serialize(m.JointState(position=[1.0, 2.0, 3.0]))
    with pytest.raises(CDRError, match="truncated"):
        payload_decoder(m.JointState)(data[:-20])
