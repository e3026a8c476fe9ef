"""Time to build a message class from a learned definition, by field count (100, 1,000, 10,000).

Run: ``.venv/bin/python bench/bench_definitions.py [--fields 100 1000 10000]``.

Each size is a fresh type of ``float64`` and ``uint8[]`` fields, learned from its ``.msg`` text
as a ROS 1 publisher's ``message_definition`` gives it. The steps are timed apart: rosbags'
parse (``learn``), the class (``class``), its RIHS01 hash and full definition (``spec``), its
CDR codec (first ``serialize`` and ``deserialize``) and its ROS 1 type and codec (``ros1``).
robomodel refuses a type of more than 1,024 fields (docs/reference/limits.md); the bound is
raised here, in this process only, to show how each step grows. Each step should grow about
tenfold per tenfold fields; tests/runtime/test_definition_build_cost.py checks by what is
compiled (not by a clock) that none grows with the square.
"""

from __future__ import annotations

import argparse
import dataclasses
import time
from collections.abc import Callable
from typing import Any


def _timed(step: Callable[[], Any]) -> tuple[float, Any]:
    started = time.perf_counter()
    result = step()
    return time.perf_counter() - started, result


def _row(count: int) -> list[float]:
    """The times of each step for a fresh type of ``count`` fields [s]."""
    from robomodel.runtime.msg import _resolver, deserialize, serialize
    from robomodel.runtime.msg.schema import get_message_type
    from robomodel.runtime.msg.spec import spec_of
    from robomodel.runtime.transport.ros1.ros1_types import ros1_type_named

    name = f"bench_msgs/Wide{count}"
    text = "".join(f"float64 f{i}\n" if i % 2 else f"uint8[] b{i}\n" for i in range(count))
    learn, _ = _timed(lambda: _resolver.learn_definition(name, text))
    build, cls = _timed(lambda: get_message_type(name))
    spec, _ = _timed(lambda: (spec_of(cls).rihs01, spec_of(cls).definition))
    cdr, _ = _timed(lambda: deserialize(serialize(cls()), cls))
    ros1, _ = _timed(lambda: ros1_type_named(name).encode(cls()))
    return [learn, build, spec, cdr, ros1]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fields", type=int, nargs="+", default=[100, 1_000, 10_000])
    args = parser.parse_args()

    from robomodel.runtime.msg import _resolver, definition
    from robomodel.runtime.msg.schema import get_message_type
    from robomodel.runtime.transport.ros1.ros1_types import ros1_type_named

    wide = dataclasses.replace(
        definition.LIMITS, max_fields=max(args.fields) + 1, max_flattened=10 * max(args.fields)
    )
    definition.LIMITS = wide  # this process only
    _resolver.LIMITS = wide  # type: ignore[attr-defined]
    get_message_type("std_msgs/msg/String")  # rosbags' stores loaded before timing
    ros1_type_named("std_msgs/String")

    print(f"{'fields':>7} {'learn':>8} {'class':>8} {'spec':>8} {'cdr':>8} {'ros1':>8}  [ms]")
    for count in args.fields:
        print(f"{count:>7} " + " ".join(f"{t * 1e3:>8.0f}" for t in _row(count)))


if __name__ == "__main__":
    main()
