"""The ROS domain id as rcl and rmw_zenoh read it, so robomodel joins the graph of the ROS 2
nodes started from the same shell.

- rcl ``rcl_get_default_domain_id`` (``rcl/src/rcl/domain_id.c``, ros2/rcl 9.2.0): an unset
  or empty ``ROS_DOMAIN_ID`` leaves the default; otherwise ``strtoul(text, &end, 0)`` (leading
  blanks, a sign, ``0x`` hex and ``0`` octal prefixes; trailing text after a non-zero number
  is ignored). A result of 0 with text left over is "not an integral number", and one past
  ``ULONG_MAX`` is "out of range". There is no upper bound of 232 (that is DDS's port
  arithmetic, not rcl's).
- rmw_zenoh ``rmw_init`` (``rmw_zenoh_cpp/src/rmw_init.cpp``, Jazzy 0.2.10): the default
  (``RMW_DEFAULT_DOMAIN_ID``, ``SIZE_MAX``) becomes 0; any other value is used as is, in
  decimal, as the first part of every key and token (``liveliness_utils.cpp``). So
  ``ROS_DOMAIN_ID=-1``, which strtoul turns into ``SIZE_MAX``, is domain 0 too.

``ROS_DOMAIN_ID`` wins over robomodel's own ``ROBOMODEL_DOMAIN_ID`` (read the same way); when
both are set and differ, one warning line says which one is used.
"""

from __future__ import annotations

import os

from robomodel.errors import RobomodelError
from robomodel.runtime.transport._zenoh_common import log

__all__ = ["SIZE_MAX", "DomainIdError", "domain_id_from_env", "parse_domain_id"]

SIZE_MAX = 2**64 - 1  # size_t and unsigned long on the 64-bit systems ROS 2 supports
_BLANKS = " \t\n\v\f\r"  # C's isspace in the "C" locale


class DomainIdError(RobomodelError):
    """A domain id that rcl would refuse."""


def _strtoul(text: str) -> tuple[int, str]:
    """C's ``strtoul(text, &end, 0)``: the value and the text left at ``end``.

    Overflow gives ``SIZE_MAX + 1`` here (C's ``ULONG_MAX`` with ``ERANGE``), for the caller
    to refuse.
    """
    rest = text.lstrip(_BLANKS)
    sign = 1
    if rest[:1] in ("+", "-"):
        sign = -1 if rest[0] == "-" else 1
        rest = rest[1:]
    base = 10
    if rest[:2].lower() == "0x" and rest[2:3].lower() in tuple("0123456789abcdef"):
        base, rest = 16, rest[2:]
    elif rest[:1] == "0":
        base = 8
    digits = "0123456789abcdef"[:base]
    count = 0
    while count < len(rest) and rest[count].lower() in digits:
        count += 1
    if count == 0:
        return 0, text  # no number: end is the start of the text
    value = int(rest[:count], base)
    if value > SIZE_MAX:
        return SIZE_MAX + 1, rest[count:]
    # strtoul negates in unsigned arithmetic: "-1" is ULONG_MAX
    return (value if sign > 0 else (-value) % (SIZE_MAX + 1)), rest[count:]


def parse_domain_id(text: str, *, variable: str = "ROS_DOMAIN_ID") -> int | None:
    """The domain id ``text`` names as rcl and rmw_zenoh read it; None for unset (empty).

    Raises:
        DomainIdError: where rcl refuses the value.
    """
    if text == "":
        return None
    value, rest = _strtoul(text)
    if value == 0 and rest != "":
        raise DomainIdError(
            f"{variable}={text!r} is not an integral number (as rcl reads it: a decimal, 0x hex "
            "or 0 octal number, e.g. 42)"
        )
    if value > SIZE_MAX:
        raise DomainIdError(f"{variable}={text!r} is out of range (at most {SIZE_MAX})")
    return 0 if value == SIZE_MAX else value


def domain_id_from_env() -> int:
    """``ROS_DOMAIN_ID``, else ``ROBOMODEL_DOMAIN_ID``, else 0; a conflict is reported."""
    ros = parse_domain_id(os.environ.get("ROS_DOMAIN_ID", ""))
    own_text = os.environ.get("ROBOMODEL_DOMAIN_ID", "")
    own = parse_domain_id(own_text, variable="ROBOMODEL_DOMAIN_ID")
    if ros is not None and own is not None and own != ros:
        log.warning(
            "ROBOMODEL_DOMAIN_ID=%r differs from ROS_DOMAIN_ID=%r; using ROS_DOMAIN_ID's %d, "
            "as the ROS 2 nodes beside robomodel do",
            own_text,
            os.environ["ROS_DOMAIN_ID"],
            ros,
        )
    if ros is not None:
        return ros
    return own if own is not None else 0
