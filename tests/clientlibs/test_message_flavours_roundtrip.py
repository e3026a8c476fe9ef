"""Every message type of rosbags' ROS 2 Jazzy and ROS 1 Noetic stores, in both flavours (rclpy's
rosidl classes, rospy's genpy classes): CDR bytes equal to those of robomodel's own class for
the same values, decoded back into the flavour's class with its containers (array.array,
numpy), and, for the genpy flavour, a ROS 1 round trip through ``serialize``/``deserialize``."""

from __future__ import annotations

import array
import io
from typing import Any

import numpy as np
import pytest

from robomodel.clientlibs.messages import flavoured
from robomodel.clientlibs.messages._genpy_time import TVal
from robomodel.runtime.msg import message_to_dict
from robomodel.runtime.msg.cdr import deserialize, serialize
from robomodel.runtime.msg.schema import (
    Array,
    Message,
    MessageTypeError,
    Seq,
    Spec,
    get_message_type,
)
from robomodel.runtime.transport.ros1.ros1_types import Ros1TypeError, ros1_type

typesys = pytest.importorskip("rosbags.typesys")
NUMERIC = {"float32", "float64", "int8", "uint8", "char", "int16", "uint16", "int32", "uint32",
           "int64", "uint64"}  # fmt: skip


def _value(spec: Spec, seed: int, rosidl: bool) -> Any:
    """A value of ``spec`` that is not its default, as robomodel's own class holds it, or with
    ``rosidl`` as rclpy's does (octets as bytes of length 1)."""
    if isinstance(spec, (Seq, Array)):
        count = spec.size if isinstance(spec, Array) else min(2, spec.bound or 2)
        items = [_value(spec.item, seed + i, rosidl) for i in range(count)]
        if spec.item in ("uint8", "char") or (spec.item == "byte" and not rosidl):
            return bytes(items)
        return items
    if isinstance(spec, str):
        base, _, bound = spec.partition("<=")
        if base == "string":
            return "ab"[: int(bound)] if bound else f"s{seed}"
        if base == "bool":
            return True
        if base.startswith("float"):
            return 0.5 + seed
        if base == "byte" and rosidl:
            return bytes([1 + seed % 100])
        return 1 + seed % 100
    return _message(spec, seed + 1, rosidl)


def _message(cls: type[Message], seed: int, rosidl: bool) -> Message:
    values = {n: _value(s, seed, rosidl) for n, s in cls.__fields__}
    if issubclass(cls, TVal):  # genpy's Time(secs, nsecs)
        return cls(*values.values())
    return cls(**values)


def _check_containers(msg: Message) -> None:
    """rosidl's containers: array.array for numeric sequences, numpy for fixed numeric
    arrays, nested messages of the same flavour."""
    for name, spec in msg.__fields__:
        value = getattr(msg, name)
        if isinstance(spec, (Seq, Array)) and spec.item in NUMERIC:
            expected = array.array if isinstance(spec, Seq) else np.ndarray
            assert isinstance(value, expected), (type(msg).__typename__, name, type(value))
        elif isinstance(spec, type):
            assert type(value) is spec, (type(msg).__typename__, name)
            _check_containers(value)


def _store_classes(store: str) -> list[type[Message]]:
    names = typesys.get_typestore(typesys.Stores[store]).fielddefs
    classes = []
    for name in sorted(names):
        try:
            classes.append(get_message_type(name))
        except MessageTypeError:  # a type robomodel refuses (documented limits)
            continue
    return classes


@pytest.mark.parametrize("store", ["ROS2_JAZZY", "ROS1_NOETIC"])
@pytest.mark.parametrize("flavour", ["rosidl", "genpy"])
def test_every_store_type_round_trips_in_each_flavour(store: str, flavour: str) -> None:
    classes = _store_classes(store)
    assert len(classes) > 150
    ros1_checked = 0
    for ours in classes:
        face = flavoured(ours, flavour)
        assert face.__typename__ == ours.__typename__
        assert [n for n, _ in face.__fields__] == [n for n, _ in ours.__fields__]
        msg = _message(face, 3, flavour == "rosidl")
        data = serialize(msg)
        native = _message(ours, 3, False)
        assert data == serialize(native), ours.__typename__
        assert message_to_dict(msg) == message_to_dict(native), ours.__typename__
        # defaults too: a definition's default annotation (Quaternion's w 1) is the flavour's
        assert message_to_dict(face()) == message_to_dict(ours()), ours.__typename__
        back = deserialize(data, face)
        assert type(back) is face
        assert back == msg, ours.__typename__
        if flavour == "rosidl":
            _check_containers(back)
            continue
        if store != "ROS1_NOETIC":
            continue
        try:
            ros1_type(face)
        except Ros1TypeError:  # a ROS 2-only type: no ROS 1 wire
            continue
        buff = io.BytesIO()
        msg.serialize(buff)  # type: ignore[attr-defined]
        again = face().deserialize(buff.getvalue())  # type: ignore[attr-defined]
        assert type(again) is face, ours.__typename__
        out = io.BytesIO()
        again.serialize(out)  # ROS 1's version of a type may lack fields ROS 2's has (Range)
        assert out.getvalue() == buff.getvalue(), ours.__typename__
        ros1_checked += 1
    if flavour == "genpy" and store == "ROS1_NOETIC":
        assert ros1_checked > 100
