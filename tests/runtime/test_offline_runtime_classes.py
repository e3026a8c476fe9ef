"""The offline generator (tools/gen_msgs.py, which writes robomodel's own modules) and the run-time
builder (msg._from_definition, which the resolver uses for every other type) make equal classes
from the same definitions, with equal CDR bytes (and, for ROS 1 types, equal ROS 1 bytes): for
every message of rosbags' ROS 2 Jazzy and ROS 1 Noetic stores."""

from __future__ import annotations

import importlib
import sys
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import pytest

from robomodel.runtime.msg import message_to_dict
from robomodel.runtime.msg._from_definition import build_message_class
from robomodel.runtime.msg.cdr import deserialize, serialize
from robomodel.runtime.msg.schema import (
    Array,
    Message,
    Seq,
    Spec,
    is_byte_array,
    message_type_names,
)

typesys = pytest.importorskip("rosbags.typesys")
ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))
import gen_msgs  # noqa: E402

STORES = {"ROS2_JAZZY": False, "ROS1_NOETIC": True}  # store -> its definitions are ROS 1's


def _runtime_classes(fielddefs: dict[str, Any], *, ros1: bool) -> dict[str, type[Message]]:
    """Every message of the store as the resolver builds it (nested types from the store
    too, not robomodel's own classes, so both sides come from the same definitions)."""
    built: dict[str, type[Message]] = {}

    def lookup(name: str) -> type[Message]:
        if name not in built:
            built[name] = build_message_class(name, fielddefs[name], lookup, ros1=ros1)
        return built[name]

    for name in fielddefs:
        lookup(name)
    return built


@pytest.fixture(scope="module", params=sorted(STORES))
def both(
    request: pytest.FixtureRequest, tmp_path_factory: pytest.TempPathFactory
) -> Iterator[tuple[str, dict[str, type[Message]], dict[str, type[Message]]]]:
    """(store, offline classes, run-time classes) by type name."""
    store, ros1 = request.param, STORES[request.param]
    fielddefs = dict(typesys.get_typestore(typesys.Stores[store]).fielddefs)
    base = f"offline_{store.lower()}"
    root = tmp_path_factory.mktemp(store)
    (root / base).mkdir()
    (root / base / "__init__.py").write_text("")
    texts = gen_msgs.store_modules(fielddefs, base=base, ros1=ros1, source=store)
    for package, text in texts.items():
        (root / base / f"{package}.py").write_text(text)
    registered = set(message_type_names())
    sys.path.insert(0, str(root))
    try:
        offline: dict[str, type[Message]] = {}
        for package in texts:
            module = importlib.import_module(f"{base}.{package}")
            for name in module.__all__:
                cls = getattr(module, name)
                offline[cls.__typename__] = cls
        yield store, offline, _runtime_classes(fielddefs, ros1=ros1)
    finally:
        sys.path.remove(str(root))
        for name in [m for m in sys.modules if m.split(".")[0] == base]:
            del sys.modules[name]
    assert set(message_type_names()) == registered  # neither path registered a class


def _shape(spec: Spec) -> Any:
    """A spec with nested classes by type name, to compare specs of two class families."""
    if isinstance(spec, Seq):
        return ("seq", _shape(spec.item), spec.bound)
    if isinstance(spec, Array):
        return ("array", _shape(spec.item), spec.size)
    return spec if isinstance(spec, str) else spec.__typename__


def _sample(spec: Spec, cls_of: Callable[[str], type[Message]], seed: int) -> Any:
    """A value of ``spec`` that is not its default (every field then counts on the wire)."""
    if is_byte_array(spec):
        size = spec.size if isinstance(spec, Array) else 3
        return bytes((seed + i) % 256 for i in range(size))
    if isinstance(spec, Seq):
        count = 2 if spec.bound is None else min(2, spec.bound)
        return [_sample(spec.item, cls_of, seed + i) for i in range(count)]
    if isinstance(spec, Array):
        return [_sample(spec.item, cls_of, seed + i) for i in range(spec.size)]
    if isinstance(spec, str):
        base, _, bound = spec.partition("<=")
        if base == "string":
            return "ab"[: int(bound)] if bound else f"s{seed}"
        if base == "bool":
            return True
        if base.startswith("float"):
            return 0.5 + seed
        return 1 + seed % 100
    nested = cls_of(spec.__typename__)
    return nested(**{n: _sample(s, cls_of, seed + 1) for n, s in nested.__fields__})


def test_every_store_type_is_built_alike_on_both_paths(
    both: tuple[str, dict[str, type[Message]], dict[str, type[Message]]],
) -> None:
    store, offline, runtime = both
    assert set(offline) == set(runtime)
    assert len(offline) > 150, store
    for name, cls in offline.items():
        other = runtime[name]
        assert cls.__name__ == other.__name__, name
        assert [(n, _shape(s)) for n, s in cls.__fields__] == [
            (n, _shape(s)) for n, s in other.__fields__
        ], name
        assert tuple(cls.__constants__) == tuple(other.__constants__), name
        for c_name, _, value in cls.__constants__:
            assert getattr(cls, c_name) == getattr(other, c_name) == value, name
        assert message_to_dict(cls()) == message_to_dict(other()), name


def test_every_store_type_gives_equal_bytes_on_both_paths(
    both: tuple[str, dict[str, type[Message]], dict[str, type[Message]]],
) -> None:
    _, offline, runtime = both
    for name, cls in offline.items():
        other = runtime[name]
        mine = cls(**{n: _sample(s, offline.__getitem__, 7) for n, s in cls.__fields__})
        theirs = other(**{n: _sample(s, runtime.__getitem__, 7) for n, s in other.__fields__})
        data = serialize(mine)
        assert data == serialize(theirs), name
        assert serialize(cls()) == serialize(other()), name
        # each path reads what the other wrote
        assert message_to_dict(deserialize(data, other)) == message_to_dict(mine), name
        assert message_to_dict(deserialize(serialize(theirs), cls)) == message_to_dict(theirs)


def test_ros1_bytes_are_equal_on_both_paths(
    both: tuple[str, dict[str, type[Message]], dict[str, type[Message]]],
) -> None:
    from robomodel.runtime.transport.ros1.ros1_codec import make_codec
    from robomodel.runtime.transport.ros1.ros1_fields import special_field

    store, offline, runtime = both
    if not STORES[store]:
        pytest.skip("ROS 1 bytes are the ROS 1 store's")
    fielddefs = typesys.get_typestore(typesys.Stores[store]).fielddefs
    checked = 0
    for name, cls in offline.items():
        if name.startswith("builtin_interfaces/"):
            continue  # ROS 1's time and duration are fields of their own, not these messages
        mine = cls(**{n: _sample(s, offline.__getitem__, 3) for n, s in cls.__fields__})
        other = runtime[name]
        theirs = other(**{n: _sample(s, runtime.__getitem__, 3) for n, s in other.__fields__})
        encode_mine, decode_mine = make_codec(name, fielddefs, offline.get, special_field)
        encode_theirs, decode_theirs = make_codec(name, fielddefs, runtime.get, special_field)
        data = encode_mine(mine, 0)
        assert data == encode_theirs(theirs, 0), name
        # (a Header's seq is the codec's argument, not the message's: compare decoded with decoded)
        assert message_to_dict(decode_theirs(data)) == message_to_dict(decode_mine(data)), name
        checked += 1
    assert checked > 150
