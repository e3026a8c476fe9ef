"""Whether a message type uses ``char`` anywhere: rosidl hashes it as uint8, rosbags (as ROS 1
does) as a char of its own, so the two disagree on such types' RIHS01 hashes."""

from __future__ import annotations

from robomodel.runtime.msg.schema import Array, Message, Seq


def has_char(kind: type[Message], seen: set[str] | None = None) -> bool:
    seen = set() if seen is None else seen
    if kind.__typename__ in seen:
        return False
    seen.add(kind.__typename__)
    for _, spec in kind.__fields__:
        while isinstance(spec, (Seq, Array)):
            spec = spec.item
        if spec == "char" or (not isinstance(spec, str) and has_char(spec, seen)):
            return True
    return False
