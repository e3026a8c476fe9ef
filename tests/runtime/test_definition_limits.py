"""Bounds on the definitions robomodel builds classes from (docs/reference/limits.md): fields
and constants per type, nesting depth and flattened size, for learned definitions and package
files alike; and a class is built with no lock held, so one large type does not hold up every
other lookup."""

from __future__ import annotations

import threading
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from robomodel.runtime.msg import _resolver, get_message_type
from robomodel.runtime.msg.definition import LIMITS
from robomodel.runtime.msg.schema import MessageTypeError
from tests.timing import scaled

pytest.importorskip("rosbags.typesys")

SEPARATOR = "=" * 80


def _section(name: str, body: str) -> str:
    return f"{SEPARATOR}\nMSG: {name}\n{body}"


def test_a_huge_definition_is_refused_at_once() -> None:
    """76,000 int32 fields (977 KB, under a ROS 1 header's 1 MB cap) are refused before rosbags
    parses them or a class is built (which took minutes and 600 MB)."""
    text = "".join(f"int32 field_{i}\n" for i in range(76_000))
    started = time.monotonic()
    with pytest.raises(MessageTypeError) as info:
        _resolver.learn_definition("huge_msgs/Wide", text)
    assert time.monotonic() - started < scaled(2.0)
    assert str(info.value) == (
        f"the definition of huge_msgs/Wide: huge_msgs/msg/Wide has more than {LIMITS.max_fields}"
        " fields and constants (robomodel's bound, docs/reference/limits.md)"
    )
    with pytest.raises(MessageTypeError, match="unknown message type"):
        get_message_type("huge_msgs/Wide")


def test_the_field_bound_is_exact() -> None:
    at_bound = "".join(f"int8 f{i}\n" for i in range(LIMITS.max_fields))
    _resolver.learn_definition("bound_msgs/AtBound", at_bound)
    assert len(get_message_type("bound_msgs/AtBound").__fields__) == LIMITS.max_fields
    with pytest.raises(MessageTypeError, match=r"more than 1024 fields"):
        _resolver.learn_definition("bound_msgs/PastBound", at_bound + "int8 one_more\n")
    # a type description has no text: its fields are counted as they are
    fields = [(f"f{i}", (1, ("int8", 0))) for i in range(LIMITS.max_fields + 1)]
    with pytest.raises(MessageTypeError, match=r"^bound_msgs/msg/Described: more than 1024"):
        _resolver.learn_fielddefs({"bound_msgs/msg/Described": ((), fields)})


def test_deep_nesting_is_refused() -> None:
    depth = LIMITS.max_depth + 1
    text = "Level1 next\n" + "".join(
        _section(f"deep_msgs/Level{i}", f"Level{i + 1} next\n") for i in range(1, depth - 1)
    )
    text += _section(f"deep_msgs/Level{depth - 1}", "int32 end\n")
    with pytest.raises(MessageTypeError, match=r"nested more than 32 deep"):
        _resolver.learn_definition("deep_msgs/Level0", text)


def test_a_large_flattened_size_is_refused() -> None:
    """300 x 300 leaves through fixed arrays: few fields per type, 90,000 once expanded."""
    text = "Mid[300] mids\n" + _section("flat_msgs/Mid", "Leaf[300] leaves\n")
    text += _section("flat_msgs/Leaf", "int32 x\n")
    with pytest.raises(MessageTypeError, match=r"^flat_msgs/msg/Top: more than 65536 fields once"):
        _resolver.learn_definition("flat_msgs/Top", text)


@pytest.fixture
def deep_package(tmp_path: Path) -> Iterator[Path]:
    package = tmp_path / "ws" / "nest_msgs"
    (package / "msg").mkdir(parents=True)
    (package / "package.xml").write_text(
        '<package format="3"><name>nest_msgs</name><version>0.0.0</version></package>'
    )
    for i in range(LIMITS.max_depth + 5):
        (package / "msg" / f"N{i}.msg").write_text(f"N{i + 1} next\n")
    (package / "msg" / f"N{LIMITS.max_depth + 5}.msg").write_text("int32 end\n")
    (package / "msg" / "Wide.msg").write_text("Mid[300] mids\n")
    (package / "msg" / "Mid.msg").write_text("std_msgs/Header[300] headers\n")
    _resolver.configure(package_paths=(tmp_path / "ws",))
    yield package
    _resolver.configure(package_paths=())


def test_package_files_are_bounded_too(deep_package: Path) -> None:
    with pytest.raises(MessageTypeError, match=r"^nest_msgs/msg/N0: message types nested more"):
        get_message_type("nest_msgs/N0")
    assert get_message_type("nest_msgs/N10").__typename__ == "nest_msgs/msg/N10"  # 27 deep
    # Header is 4 fields expanded (stamp's two, frame_id): 300 x 300 x 4
    with pytest.raises(MessageTypeError, match=r"^nest_msgs/msg/Wide: more than 65536 fields"):
        get_message_type("nest_msgs/Wide")


def test_no_lock_is_held_while_a_class_is_built(monkeypatch: pytest.MonkeyPatch) -> None:
    """While one thread builds a type, another thread's lookup of another type completes."""
    _resolver.learn_definition("slow_msgs/Slow", "int32 a\n")
    _resolver.learn_definition("slow_msgs/Quick", "int32 b\n")
    building, release = threading.Event(), threading.Event()
    real = _resolver.build_message_class

    def slow_build(name: str, *args: Any, **kwargs: Any) -> Any:
        if name == "slow_msgs/msg/Slow":
            building.set()
            assert release.wait(scaled(30.0))
        return real(name, *args, **kwargs)

    monkeypatch.setattr(_resolver, "build_message_class", slow_build)
    results: dict[str, Any] = {}
    slow = threading.Thread(target=lambda: results.update(slow=get_message_type("slow_msgs/Slow")))
    slow.start()
    try:
        assert building.wait(scaled(30.0))
        quick = threading.Thread(
            target=lambda: results.update(quick=get_message_type("slow_msgs/Quick"))
        )
        quick.start()
        quick.join(scaled(30.0))
        assert "quick" in results and "slow" not in results
    finally:
        release.set()
        slow.join(scaled(30.0))
    assert results["slow"] is get_message_type("slow_msgs/Slow")  # kept once built
