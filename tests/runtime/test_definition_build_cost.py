"""A class built from a learned definition costs time linear in its fields (docs/reference/limits.md):
checked by what is compiled, not by a clock. Building a class, its RIHS01 hash, its CDR codec
and its ROS 1 type and codec compiles generated source; CPython compiles three constructs in
time quadratic in their size (a call's keywords, an f-string's parts, a nested function's free
variables: dataclasses' own ``__init__`` and ``__repr__``, and a decoder calling the class by
keyword, took seconds at 10,000 fields). The measured times are in bench/bench_definitions.py."""

from __future__ import annotations

import ast
import builtins
import dataclasses
from collections.abc import Iterator
from typing import Any

import pytest

from robomodel.runtime.msg import _resolver, deserialize, get_message_type, serialize
from robomodel.runtime.msg.definition import LIMITS
from robomodel.runtime.msg.typehash import type_hash

pytest.importorskip("rosbags.typesys")

# far below any size where the quadratic constructs cost anything, far above a real type's
WIDE = 64


def _compiled_while(build: Any) -> list[str]:
    """The source texts that ``exec``/``compile`` are given while ``build()`` runs."""
    sources: list[str] = []
    real_exec, real_compile = builtins.exec, builtins.compile

    def record(source: Any) -> None:
        if isinstance(source, str):
            sources.append(source)

    def exec_(source: Any, *args: Any, **kwargs: Any) -> Any:
        record(source)
        return real_exec(source, *args, **kwargs)

    def compile_(source: Any, *args: Any, **kwargs: Any) -> Any:
        record(source)
        return real_compile(source, *args, **kwargs)

    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(builtins, "exec", exec_)
        patch.setattr(builtins, "compile", compile_)
        build()
    return sources


def _quadratic_constructs(source: str) -> Iterator[str]:
    """Constructs whose compile time grows with the square of their size, past ``WIDE``."""
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Call) and len(node.keywords) > WIDE:
            yield f"a call with {len(node.keywords)} keyword arguments"
        if isinstance(node, ast.JoinedStr) and len(node.values) > WIDE:
            yield f"an f-string of {len(node.values)} parts"
        if isinstance(node, ast.FunctionDef) and len(node.args.args) > WIDE:
            inner = [n for n in ast.walk(node) if isinstance(n, ast.FunctionDef) and n is not node]
            if inner:
                yield f"a function of {len(node.args.args)} parameters closed over by another"


def _build(name: str, count: int) -> None:
    text = "".join(f"float64 f{i}\nuint8[] b{i}\n" for i in range(count // 2))
    _resolver.learn_definition(name, text)
    cls = get_message_type(name)
    type_hash(cls)
    assert deserialize(serialize(cls()), cls) == cls()
    from robomodel.runtime.transport.ros1.ros1_types import ros1_type_named

    ros1 = ros1_type_named(name)
    assert ros1.decode(ros1.encode(cls())) == cls()


@pytest.fixture(autouse=True)
def _stores_loaded() -> None:
    """rosbags' stores and robomodel's modules are imported (their classes compiled) before
    anything is recorded: only what the wide type costs is looked at."""
    _build("wide_msgs/Small", 2)


def test_building_a_wide_class_compiles_nothing_quadratic() -> None:
    sources = _compiled_while(lambda: _build("wide_msgs/AtBound", LIMITS.max_fields))
    assert len(sources) >= 3  # the class's __init__, its CDR codec and its ROS 1 codec
    found = [c for source in sources for c in _quadratic_constructs(source)]
    assert found == []


def test_compiled_source_grows_linearly_with_the_fields() -> None:
    small = _compiled_while(lambda: _build("wide_msgs/Quarter", LIMITS.max_fields // 4))
    large = _compiled_while(lambda: _build("wide_msgs/Full", LIMITS.max_fields))
    ratio = sum(map(len, large)) / sum(map(len, small))
    assert 3.0 < ratio < 5.0


def test_dataclasses_own_methods_would_be_caught() -> None:
    """The check above sees the construct it guards against: dataclasses' ``__init__``."""
    fields = [(f"f{i}", float, dataclasses.field(default=0.0)) for i in range(WIDE + 1)]
    sources = _compiled_while(lambda: dataclasses.make_dataclass("Wide", fields))
    found = {c.split(" of ")[0] for s in sources for c in _quadratic_constructs(s)}
    assert found == {"an f-string", "a function"}


def test_the_class_methods_behave_as_dataclasses_ones() -> None:
    _resolver.learn_definition("wide_msgs/Behave", "float64 x\nstring self\nint32[] values\n")
    cls = get_message_type("wide_msgs/Behave")
    msg = cls(1.5, "a", values=[1])  # type: ignore[call-arg]
    assert repr(msg) == "Behave(x=1.5, self='a', values=[1])"
    assert cls() == cls(0.0, "", [])  # type: ignore[call-arg]
    assert cls().values is not cls().values  # type: ignore[attr-defined]
    assert dataclasses.replace(msg, x=2.0).x == 2.0  # type: ignore[attr-defined]
    with pytest.raises(TypeError):
        cls(nope=1)  # type: ignore[call-arg]
