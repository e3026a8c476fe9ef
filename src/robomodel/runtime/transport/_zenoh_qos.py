"""rmw_zenoh's QoS string, the last part of an entity's liveliness token.

Transcribed from ros2/rmw_zenoh ``rmw_zenoh_cpp/src/detail/liveliness_utils.cpp`` (Jazzy
0.2.10, ``ros2-gbp/rmw_zenoh-release`` tag ``release/jazzy/rmw_zenoh_cpp/0.2.10-1``):

- ``qos_to_keyexpr``: ``reliability:durability:history,depth:deadline_s,deadline_ns:
  lifespan_s,lifespan_ns:liveliness,lease_s,lease_ns``, rmw's enum values in decimal, each
  value equal to rmw_zenoh's default (``qos.cpp``: reliable, volatile, keep last 42, infinite
  durations, automatic liveliness) left empty. A duration's seconds and nanoseconds are
  compared with ``RMW_DURATION_INFINITE`` (9223372036 s, 854775807 ns) one by one.
- ``keyexpr_to_qos``: at least six ``:`` parts, at least two ``,`` parts in history, deadline
  and lifespan and three in liveliness (further parts are ignored); an empty value is the
  default; enum values from rmw's tables (``str_to_qos_*``: no MANUAL_BY_NODE, 2, for
  liveliness); numbers by ``str_to_size_t`` (``strtoull`` base 10, no leading ``-``, nothing
  after the number, at most 2**64 - 1).

What rmw_zenoh adapts before encoding (``QoS::best_available_qos``: a depth of 0 is 42, system
default and unknown policies are the defaults) is read back the same way: robomodel's
profile has no "system default" to keep.
"""

from __future__ import annotations

from robomodel.runtime.qos import Durability, History, Liveliness, QoSProfile, Reliability

__all__ = ["DEFAULT_DEPTH", "qos_from_key", "qos_to_key"]

DEFAULT_DEPTH = 42
_INFINITE_S, _INFINITE_NS = 9223372036, 854775807  # rmw/time.h RMW_DURATION_INFINITE
_U64_MAX = 2**64 - 1
_BLANKS = " \t\n\v\f\r"

# rmw/types.h enum values; system default (0) and unknown read as rmw_zenoh's defaults, as
# best_available_qos adapts them, and best available (reliability and durability 4,
# liveliness 5) as the default too (what rmw_zenoh offers).
_RELIABILITY = {"0": Reliability.RELIABLE, "1": Reliability.RELIABLE,
                "2": Reliability.BEST_EFFORT, "3": Reliability.RELIABLE,
                "4": Reliability.RELIABLE}  # fmt: skip
_DURABILITY = {"0": Durability.VOLATILE, "1": Durability.TRANSIENT_LOCAL,
               "2": Durability.VOLATILE, "3": Durability.VOLATILE, "4": Durability.VOLATILE}  # fmt: skip
_HISTORY = {"0": History.KEEP_LAST, "1": History.KEEP_LAST, "2": History.KEEP_ALL,
            "3": History.KEEP_LAST}  # fmt: skip
_LIVELINESS = {"0": Liveliness.AUTOMATIC, "1": Liveliness.AUTOMATIC,
               "3": Liveliness.MANUAL_BY_TOPIC, "4": Liveliness.AUTOMATIC,
               "5": Liveliness.AUTOMATIC}  # fmt: skip


def _duration(value_ns: int | None) -> str:
    sec, nsec = (_INFINITE_S, _INFINITE_NS) if value_ns is None else divmod(value_ns, 10**9)
    return f"{'' if sec == _INFINITE_S else sec},{'' if nsec == _INFINITE_NS else nsec}"


def qos_to_key(qos: QoSProfile) -> str:
    """``qos_to_keyexpr`` (``::,10:,:,:,,`` is rclcpp's default)."""
    reliability = "" if qos.reliability is Reliability.RELIABLE else "2"
    durability = "" if qos.durability is Durability.VOLATILE else "1"
    history = "" if qos.history is History.KEEP_LAST else "2"
    depth = "" if qos.depth in (0, DEFAULT_DEPTH) else str(qos.depth)
    liveliness = "" if qos.liveliness is Liveliness.AUTOMATIC else "3"
    return (
        f"{reliability}:{durability}:{history},{depth}:{_duration(qos.deadline_ns)}:"
        f"{_duration(qos.lifespan_ns)}:{liveliness},{_duration(qos.liveliness_lease_ns)}"
    )


def _size_t(text: str, default: int) -> int | None:
    """``str_to_size_t``: empty is the default; None where rmw_zenoh refuses the text."""
    if not text:
        return default
    if text[0] == "-":
        return None
    rest = text.lstrip(_BLANKS)  # strtoull skips leading white space and takes a sign
    negative = rest[:1] == "-"
    rest = rest[1:] if rest[:1] in ("+", "-") else rest
    if not rest or not rest.isascii() or not rest.isdigit():
        return None  # no number, or text after it
    value = int(rest)
    if value > _U64_MAX:
        return None
    return (-value) % (_U64_MAX + 1) if negative else value


def _duration_ns(sec_text: str, nsec_text: str) -> int | bool | None:
    """A duration [ns] from its two parts; None for infinite, False where refused."""
    sec, nsec = _size_t(sec_text, _INFINITE_S), _size_t(nsec_text, _INFINITE_NS)
    if sec is None or nsec is None:
        return False
    if (sec, nsec) == (_INFINITE_S, _INFINITE_NS):
        return None
    return sec * 10**9 + nsec


def qos_from_key(text: str) -> QoSProfile | None:
    """``keyexpr_to_qos``: the profile, or None where rmw_zenoh refuses the string."""
    parts = text.split(":")
    if len(parts) < 6:
        return None
    history, deadline, lifespan = (parts[i].split(",") for i in (2, 3, 4))
    liveliness = parts[5].split(",")
    if min(len(history), len(deadline), len(lifespan)) < 2 or len(liveliness) < 3:
        return None
    kinds = (
        _RELIABILITY.get(parts[0] or "1"),
        _DURABILITY.get(parts[1] or "2"),
        _HISTORY.get(history[0] or "1"),
        _LIVELINESS.get(liveliness[0] or "1"),
    )
    depth = _size_t(history[1], DEFAULT_DEPTH)
    durations = [_duration_ns(*d[:2]) for d in (deadline, lifespan, liveliness[1:])]
    if None in kinds or depth is None or any(d is False for d in durations):
        return None
    reliability, durability, history_kind, liveliness_kind = kinds
    deadline_ns, lifespan_ns, lease_ns = (d if isinstance(d, int) else None for d in durations)
    return QoSProfile(
        depth or DEFAULT_DEPTH,
        durability,  # type: ignore[arg-type]
        reliability,  # type: ignore[arg-type]
        history_kind,  # type: ignore[arg-type]
        deadline_ns,
        lifespan_ns,
        liveliness_kind,  # type: ignore[arg-type]
        lease_ns,
    )
