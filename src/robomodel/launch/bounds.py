"""The launch layer's bounds, as xacro's: value size and total work of one load.

A substitution result over :data:`MAX_VALUE_CHARS` (xacro's ``max_length``) is refused at the
substitution that makes it, so an arg doubling itself 39 times stops at the 24th step instead
of reaching gigabytes. :data:`MAX_WORK` bounds what one load processes (one unit per element or
entity, :data:`INCLUDE_WORK` per include, which reads and parses a file), so includes fanning
out exponentially are refused in about a second; real launch files use well under 1 % of it.
"""

from __future__ import annotations

__all__ = ["INCLUDE_WORK", "MAX_VALUE_CHARS", "MAX_WORK", "value_too_long", "work_exceeded"]

MAX_VALUE_CHARS = 10_000_000
MAX_WORK = 200_000
INCLUDE_WORK = 20


def value_too_long(length: int) -> str | None:
    """The error message for a substituted value of ``length`` characters, or None if fine."""
    if length <= MAX_VALUE_CHARS:
        return None
    return (
        f"a substitution result of {length:,} characters is over the {MAX_VALUE_CHARS:,}-"
        "character limit (does an arg or variable double itself?)"
    )


def work_exceeded(work: int, unit: str, files_read: int) -> str | None:
    """The error message for ``work`` units done in one load, or None if within the bound.

    ``unit`` is what one unit counts ("element" for roslaunch XML, "action" for ROS 2).
    """
    if work <= MAX_WORK:
        return None
    return (
        f"this launch processes more than {MAX_WORK:,} units of work (one per {unit}, "
        f"{INCLUDE_WORK} per include): includes fan out exponentially? "
        f"({files_read} files read so far)"
    )
