"""The test tiers: the markers the conftest derives, and the guard that keeps the in-process
tier (``make test-fast``) in the process."""

from __future__ import annotations

import contextlib
import os
import socket
import subprocess
import sys
from collections.abc import Callable

import pytest

from tests.tiers import (
    FIXTURE_TIERS,
    MARKERS,
    PATH_TIERS,
    TierViolation,
    child_pids,
    in_process_only,
    is_loopback_bind,
    tiers_of,
)
from tests.timing import wait_until

_EXECUTE_CHILD = subprocess.Popen._execute_child  # type: ignore[attr-defined]


def test_the_in_process_tier_runs_under_the_guard() -> None:
    """This test has no tier marker: the conftest's guard is on while it runs."""
    assert subprocess.Popen._execute_child is not _EXECUTE_CHILD  # type: ignore[attr-defined]


def test_a_fixture_puts_its_tests_in_its_tier(
    request: pytest.FixtureRequest, check_urdf: Callable[..., object]
) -> None:
    """check_urdf runs a reference tool: a test that asks for it is marked ``process``."""
    assert request.node.get_closest_marker("process") is not None
    assert request.node.get_closest_marker("browser") is None


def test_tiers_come_from_the_fixture_closure_and_the_path() -> None:
    assert tiers_of("tests/xacro/test_api.py::test_x", [("tests", "cli")]) == set()
    assert tiers_of("tests/xacro/test_api.py::test_x", [("tests", "check_urdf")]) == {"process"}
    # where a fixture is defined counts, not only its name
    assert tiers_of("tests/viewer/test_v.py::t", [("tests/viewer", "viewer")]) == {"process"}
    assert tiers_of("tests/viewer/test_v.py::t", [("tests/viewer/test_v.py", "viewer")]) == set()
    assert tiers_of("tests/sim/test_build.py::test_x", []) == {"sim"}
    assert tiers_of("tests/simulated/test_x.py::test_x", []) == set()  # a folder, not a prefix


def test_a_test_is_named_by_its_function_and_takes_its_parameters_along(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    monkeypatch.setitem(PATH_TIERS, "tests/x/test_y.py::test_a", ("bus",))
    assert tiers_of("tests/x/test_y.py::test_a", []) == {"bus"}
    assert tiers_of("tests/x/test_y.py::test_a[1-<include x>]", []) == {"bus"}
    assert tiers_of("tests/x/test_y.py::test_ab", []) == set()
    assert tiers_of("tests/x/test_z.py::test_a", []) == set()


def test_the_tables_name_registered_markers_only() -> None:
    used = {m for table in (FIXTURE_TIERS, PATH_TIERS) for ms in table.values() for m in ms}
    assert used <= {*MARKERS, "slow"}


@pytest.mark.process
def test_the_guard_refuses_a_process() -> None:
    with pytest.raises(TierViolation, match="mark it 'process'"), in_process_only("t"):
        subprocess.run([sys.executable, "-c", "pass"], check=False)
    with pytest.raises(TierViolation, match=r"os\.system"), in_process_only("t"):
        os.system("true")


@pytest.mark.process
@pytest.mark.process
def test_child_pids_lists_a_running_child_and_not_a_reaped_one() -> None:
    child = subprocess.Popen(
        [sys.executable, "-c", "import sys; sys.stdin.read()"], stdin=subprocess.PIPE
    )
    try:
        assert child.pid in child_pids()
    finally:
        child.communicate(b"")
    assert child.pid not in child_pids()


@pytest.mark.process
def test_the_guard_fails_at_the_end_when_the_refusal_was_caught() -> None:
    """Code under test that catches every error (and turns it into its own) still fails."""
    with (
        pytest.raises(TierViolation, match="t starts a process"),
        in_process_only("t"),
        contextlib.suppress(Exception),
    ):
        subprocess.run(["true"], check=False)


@pytest.mark.bus
def test_the_guard_refuses_a_zenoh_session() -> None:
    import zenoh

    with pytest.raises(TierViolation, match=r"opens a Zenoh session.*'bus'"), in_process_only("t"):
        zenoh.open(zenoh.Config())


@pytest.mark.bus
def test_the_guard_refuses_a_socket_bound_beyond_loopback() -> None:
    with in_process_only("t"), socket.socket() as loopback:
        loopback.bind(("127.0.0.1", 0))
    for host in ("0.0.0.0", ""):
        with (
            pytest.raises(TierViolation, match=r"binds a socket.*'bus'"),
            in_process_only("t"),
            socket.socket() as every,
        ):
            every.bind((host, 0))


def test_loopback_binds() -> None:
    assert is_loopback_bind(socket.AF_INET, ("127.0.0.1", 0))
    assert is_loopback_bind(socket.AF_INET, ("127.5.0.1", 0))
    assert is_loopback_bind(socket.AF_INET6, ("::1", 0, 0, 0))
    assert is_loopback_bind(socket.AF_INET, ("localhost", 0))
    assert is_loopback_bind(socket.AF_UNIX, "/tmp/x.sock")
    assert not is_loopback_bind(socket.AF_INET, ("0.0.0.0", 0))
    assert not is_loopback_bind(socket.AF_INET, ("", 0))
    assert not is_loopback_bind(socket.AF_INET6, ("::", 0, 0, 0))
    assert not is_loopback_bind(socket.AF_INET, ("192.168.1.4", 0))


def test_wait_until_returns_the_value_and_names_what_it_waited_for() -> None:
    calls = iter([0, None, [], "ready"])
    assert wait_until(lambda: next(calls), 5, what="x", interval_s=0) == "ready"
    with pytest.raises(AssertionError, match=r"timed out after .* s waiting for the door \(3\)"):
        wait_until(lambda: False, 0.01, what=lambda: "the door (3)", interval_s=0.001)


def test_make_test_fast_s_selection_leaves_the_other_tiers_out() -> None:
    """``-m`` selects by the tier marks (they are set as each test is collected, before
    pytest's selection): the fast tier's expression leaves out a module of the ROS 1 tier
    and keeps an in-process one."""
    from tests.conftest import ROOT

    makefile = (ROOT / "Makefile").read_text()
    fast = next(line for line in makefile.splitlines() if line.startswith("FAST_TIER :="))
    expression = fast.split(":=", 1)[1].strip()
    listed = subprocess.run(
        [sys.executable, "-m", "pytest", "--collect-only", "-q", "-n", "0",
         "-m", expression, "tests/ros1wire/test_debian_ros1.py", "tests/test_tiers.py"],
        capture_output=True, text=True, cwd=ROOT, timeout=120,
    )  # fmt: skip
    ids = [line for line in listed.stdout.splitlines() if "::" in line]
    assert ids and all(i.startswith("tests/test_tiers.py::") for i in ids), listed.stdout
    assert "test_make_test_fast_s_selection" not in listed.stdout  # a process test itself
