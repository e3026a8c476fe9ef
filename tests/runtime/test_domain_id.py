"""The domain id as rcl reads ``ROS_DOMAIN_ID``.

Expected values follow ros2/rcl ``rcl/src/rcl/domain_id.c`` (``rcl_get_default_domain_id``:
``strtoul(text, &end, 0)``; 0 with text left over is refused, overflow is refused, other
trailing text is ignored) and rmw_zenoh Jazzy 0.2.10 ``src/rmw_init.cpp`` (``SIZE_MAX``,
``RMW_DEFAULT_DOMAIN_ID``, becomes 0). The C behaviour of ``strtoul`` for each string is C99
7.20.1.4: leading white space, an optional sign, ``0x`` for base 16 and ``0`` for base 8.
"""

from __future__ import annotations

import logging
import subprocess

import pytest

from robomodel.runtime.transport._domain_id import (
    SIZE_MAX,
    DomainIdError,
    domain_id_from_env,
    parse_domain_id,
)
from tests.conftest import ROBOMODEL
from tests.timing import scaled, wait_until


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("", None),  # empty: rcl keeps the default
        ("0", 0),
        ("42", 42),
        ("232", 232),
        ("233", 233),  # no DDS bound: rcl accepts it, rmw_zenoh keys by it
        ("100000", 100000),
        (" \t42", 42),  # strtoul skips leading white space
        ("+42", 42),
        ("0x2a", 42),  # base 0: hexadecimal
        ("0X2A", 42),
        ("052", 42),  # base 0: octal
        ("42abc", 42),  # non-zero with trailing text: rcl does not look at end
        ("7 ", 7),
        ("-1", 0),  # strtoul: ULONG_MAX, which is RMW_DEFAULT_DOMAIN_ID, which rmw_zenoh makes 0
        ("-2", SIZE_MAX - 1),
        (str(SIZE_MAX - 1), SIZE_MAX - 1),
    ],
)
def test_values_rcl_accepts(text: str, expected: int | None) -> None:
    assert parse_domain_id(text) == expected


@pytest.mark.parametrize(
    ("text", "why"),
    [
        ("abc", "not an integral number"),
        ("0abc", "not an integral number"),  # 0 with text left over
        ("08", "not an integral number"),  # octal: the 8 is left over
        ("0x", "not an integral number"),  # "0" is read, "x" is left
        (" ", "not an integral number"),
        ("-", "not an integral number"),
        (str(SIZE_MAX + 1), "out of range"),
        ("0x1" + "0" * 16, "out of range"),
    ],
)
def test_values_rcl_refuses(text: str, why: str) -> None:
    with pytest.raises(DomainIdError, match=why) as raised:
        parse_domain_id(text)
    assert "ROS_DOMAIN_ID" in str(raised.value)
    assert "\n" not in str(raised.value)


def test_ros_domain_id_wins_and_a_conflict_is_one_line(
    monkeypatch: pytest.MonkeyPatch, caplog: pytest.LogCaptureFixture
) -> None:
    monkeypatch.setenv("ROS_DOMAIN_ID", "0x10")
    monkeypatch.setenv("ROBOMODEL_DOMAIN_ID", "7")
    with caplog.at_level(logging.WARNING, logger="robomodel.runtime"):
        assert domain_id_from_env() == 16
    [record] = caplog.records
    assert "ROBOMODEL_DOMAIN_ID" in record.getMessage()
    assert "using ROS_DOMAIN_ID's 16" in record.getMessage()
    assert "\n" not in record.getMessage()
    caplog.clear()
    monkeypatch.setenv("ROBOMODEL_DOMAIN_ID", "16")  # the same domain: nothing to say
    with caplog.at_level(logging.WARNING, logger="robomodel.runtime"):
        assert domain_id_from_env() == 16
    assert not caplog.records
    monkeypatch.delenv("ROS_DOMAIN_ID")
    assert domain_id_from_env() == 16  # robomodel's own when ROS 2's is unset
    monkeypatch.setenv("ROS_DOMAIN_ID", "")  # empty is unset, as rcl reads it
    monkeypatch.delenv("ROBOMODEL_DOMAIN_ID")
    assert domain_id_from_env() == 0


def test_a_transport_keys_its_graph_by_ros_domain_id(monkeypatch: pytest.MonkeyPatch) -> None:
    """A domain past DDS's 232 works end to end: the node's token is declared under it and
    the graph read back from the router finds it (rmw_zenoh keys tokens by the number)."""
    from robomodel.runtime import Context

    monkeypatch.setenv("ROS_DOMAIN_ID", "0x1f5")  # 501
    monkeypatch.setenv("ROBOMODEL_DOMAIN_ID", "3")
    with Context("zenoh") as ctx:
        ctx.create_node("domain_probe")
        transport = ctx.transport
        assert transport.domain_id == 501  # type: ignore[attr-defined]
        session = transport.session  # type: ignore[attr-defined]
        keys: list[str] = []

        def declared() -> bool:  # the router may answer before the new token reached it
            keys[:] = [str(r.ok.key_expr) for r in session.liveliness().get("@ros2_lv/501/**")
                       if r.ok]  # fmt: skip
            return any(k.endswith("/NN/%/%/domain_probe") for k in keys)

        wait_until(declared, 10, what=lambda: f"the node's token under domain 501: {keys}")
        # nothing may answer under domain 3 (a window expected to pass empty: not scaled)
        answers = list(session.liveliness().get("@ros2_lv/3/**", timeout=0.5))
        assert not [r for r in answers if r.ok], answers  # a "Timeout" error reply is no token


def test_the_command_line_reads_domain_id_as_rcl() -> None:
    from robomodel.cli._bus import domain_id_arg

    assert domain_id_arg("0x2a") == 42
    result = subprocess.run(
        [*ROBOMODEL, "topic", "list", "--domain-id", "forty"],
        capture_output=True, text=True, timeout=scaled(60), check=False,
    )  # fmt: skip
    assert result.returncode == 2
    assert "--domain-id='forty' is not an integral number" in result.stderr.splitlines()[-1]
