"""Child processes end as a group, and Ctrl-C works however robomodel was started:
roslaunch's SIGINT, SIGTERM, SIGKILL sequence on each child's own process
group; a SIGTERM during a ``<param command=>`` load ends the command's whole tree; SIGINT
stops a verb that a script started in the background (SIGINT ignored at start)."""

from __future__ import annotations

import signal
import socket
import subprocess
import time
import uuid
from pathlib import Path

import pytest

from robomodel.launch.processes import CommandError, end_group, run_bounded
from tests.conftest import ROBOMODEL
from tests.timing import scaled, wait_until


def _alive(marker: str) -> list[str]:
    found = subprocess.run(["pgrep", "-f", marker], capture_output=True, text=True)
    return found.stdout.split()


def _gone(marker: str) -> bool:
    return not _alive(marker)


def _started(marker: str) -> bool:
    return bool(_alive(marker))


def _seconds() -> str:
    """A sleep duration no other process on the machine uses, to find ours by name."""
    return f"{900 + uuid.uuid4().int % 99}.{uuid.uuid4().int % 1000:03d}"


def test_end_group_ends_background_children_too() -> None:
    a, b = _seconds(), _seconds()
    proc = subprocess.Popen(["sh", "-c", f"sleep {a} & sleep {b}"], start_new_session=True)
    wait_until(lambda: _started(f"sleep {a}"), 30, what=f"sleep {a} to start", interval_s=0.1)
    wait_until(lambda: _started(f"sleep {b}"), 30, what=f"sleep {b} to start", interval_s=0.1)
    # the SIGINT window is expected to expire (the background sleep ignores SIGINT): not scaled
    end_group(proc, sigint_timeout_s=5, sigterm_timeout_s=2)
    # the background sleep ignores SIGINT (a non-interactive shell's background job): SIGTERM
    wait_until(lambda: _gone(f"sleep {a}"), 10, what=f"sleep {a} to end", interval_s=0.1)
    wait_until(lambda: _gone(f"sleep {b}"), 10, what=f"sleep {b} to end", interval_s=0.1)


def test_run_bounded_kills_the_tree_on_timeout() -> None:
    a = _seconds()
    with pytest.raises(CommandError, match=r"did not finish within 0\.3 s"):
        run_bounded(["sh", "-c", f"sleep {a} & sleep {a}; echo done"], timeout_s=0.3)
    wait_until(lambda: _gone(f"sleep {a}"), 10, what=f"sleep {a} to end", interval_s=0.1)


def _ros2_launch(tmp_path: Path, a: str, b: str) -> Path:
    path = tmp_path / "sleepers.launch.xml"
    path.write_text(
        "<launch>\n  <let name='x' value='1'/>\n"
        f"  <executable cmd=\"sh -c 'sleep {a} &amp; sleep {b}'\" output='screen'/>\n"
        "</launch>\n"
    )
    return path


@pytest.mark.parametrize("how", ["duration", "SIGINT", "SIGTERM"])
def test_launch_ends_its_childrens_groups(tmp_path: Path, how: str) -> None:
    a, b = _seconds(), _seconds()
    argv = [*ROBOMODEL, "launch", str(_ros2_launch(tmp_path, a, b)), "--headless"]
    argv += ["--bus", "inproc"] + (["--duration", "3"] if how == "duration" else [])
    proc = subprocess.Popen(argv, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    try:
        wait_until(lambda: _started(f"sleep {a}"), 30, what=f"sleep {a} to start", interval_s=0.1)
        if how != "duration":
            proc.send_signal(getattr(signal, how))
        _, err = proc.communicate(timeout=scaled(30))
        assert "Traceback" not in err
        wait_until(lambda: _gone(f"sleep {a}"), 10, what=f"child sleep {a} to end", interval_s=0.1)
        wait_until(lambda: _gone(f"sleep {b}"), 10, what=f"child sleep {b} to end", interval_s=0.1)
    finally:
        proc.kill()
        proc.wait()


def test_sigterm_during_a_param_command_ends_the_command_tree(tmp_path: Path) -> None:
    a = _seconds()
    path = tmp_path / "slow.launch"
    path.write_text(
        f'<launch>\n  <param name="c" command="sh -c \'sleep {a}; echo hi\'"/>\n</launch>\n'
    )
    proc = subprocess.Popen(
        [*ROBOMODEL, "launch", str(path), "--headless", "--bus", "inproc"],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
        text=True,
    )
    try:
        wait_until(lambda: _started(f"sleep {a}"), 30, what=f"sleep {a} to start", interval_s=0.1)
        proc.terminate()
        _, err = proc.communicate(timeout=scaled(20))
        assert proc.returncode == 143 and "Traceback" not in err
        wait_until(lambda: _gone(f"sleep {a}"), 10, what=f"sleep {a} to end", interval_s=0.1)
    finally:
        proc.kill()
        proc.wait()


def _listening(port: int) -> bool:
    with socket.socket() as probe:
        return probe.connect_ex(("127.0.0.1", port)) == 0


def _ignore_sigint() -> None:
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # what `robomodel ... &` in a script gets


def test_ctrl_c_works_when_started_with_sigint_ignored(tmp_path: Path) -> None:
    with socket.socket() as free:  # a port nobody listens on (one derived from the pid could be)
        free.bind(("127.0.0.1", 0))
        port = str(free.getsockname()[1])
    proc = subprocess.Popen(
        [*ROBOMODEL, "master", "-p", port],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        preexec_fn=_ignore_sigint,
    )
    try:
        deadline = time.monotonic() + scaled(30)
        while not _listening(int(port)):  # it is up: its handlers are in place
            assert proc.poll() is None and time.monotonic() < deadline, "master did not start"
            time.sleep(0.1)
        proc.send_signal(signal.SIGINT)
        _, err = proc.communicate(timeout=scaled(20))
        assert proc.returncode in (0, 130) and "Traceback" not in err
    finally:
        proc.kill()
        proc.wait()


def test_a_bus_that_hangs_on_close_does_not_keep_the_launch_alive() -> None:
    """Every node stopped, the Zenoh session's close() blocks (its runtime panicked while peers
    went away): the launch says so and exits instead of hanging."""
    script = (
        "import time\n"
        "import robomodel.launch.runner as r\n"
        "r._CLOSE_TIMEOUT_S = 0.5\n"
        "runner = r.LaunchRunner.__new__(r.LaunchRunner)\n"
        "runner.started, runner._ros1 = [], None\n"
        "runner.gui = type('G', (), {'close': lambda self: None})()\n"
        "runner.context = type('C', (), {'shutdown': lambda self: time.sleep(120)})()\n"
        "runner.shutdown()\n"
    )
    import sys

    done = subprocess.run(
        [sys.executable, "-c", script], capture_output=True, text=True, timeout=scaled(60)
    )
    assert done.returncode == 0
    assert "closing the viewer and the bus took over 0.5 s" in done.stderr
    assert "in shutdown" in done.stderr  # the runner's stack, where the close waited


def test_a_zenoh_session_that_never_closes_is_left_behind() -> None:
    import threading as _threading

    from robomodel.runtime.transport import _zenoh_common

    class Stuck:
        def close(self) -> None:
            _threading.Event().wait(scaled(30))

    before = _zenoh_common.abandoned_sessions
    assert not _zenoh_common.close_session(Stuck(), timeout_s=scaled(0.2))
    assert _zenoh_common.abandoned_sessions == before + 1
    assert _zenoh_common.close_session(type("Fine", (), {"close": lambda self: None})())


def test_an_undeclaration_that_never_returns_is_under_the_close_bound() -> None:
    """The session's undeclarations wait on the same Zenoh runtime as its close: a stuck one
    leaves the session behind within the same bound instead of hanging the caller."""
    import threading as _threading

    from robomodel.runtime.transport import _zenoh_common

    closed: list[bool] = []
    session = type("Session", (), {"close": lambda self: closed.append(True)})()
    before = _zenoh_common.abandoned_sessions
    stuck = _zenoh_common.close_session(
        session, timeout_s=scaled(0.2), before=lambda: _threading.Event().wait(scaled(30))
    )
    assert not stuck and not closed
    assert _zenoh_common.abandoned_sessions == before + 1
    order: list[str] = []
    session = type("Session", (), {"close": lambda self: order.append("close")})()
    assert _zenoh_common.close_session(session, before=lambda: order.append("undeclare"))
    assert order == ["undeclare", "close"]


def test_a_viewer_that_hangs_on_close_still_ends_on_ctrl_c() -> None:
    """Past its bound, the viewer's close shows where each thread waited and ends the process
    (130, as Ctrl-C): the page and bus it held go with it."""
    import sys

    script = (
        "import threading\n"
        "from robomodel.cli import view\n"
        "stuck = type('V', (), {'close': lambda self: threading.Event().wait(120)})()\n"
        "view._close_within(stuck, 0.5)\n"
        "print('returned')\n"
    )
    done = subprocess.run(
        [sys.executable, "-c", script], capture_output=True, text=True, timeout=scaled(60)
    )
    assert done.returncode == 130 and "returned" not in done.stdout
    assert "robomodel view: did not stop within 0.5 s; ending now" in done.stderr
    assert "_close_within" in done.stderr  # the main thread's stack, where it waited


def test_the_command_line_exits_past_an_abandoned_session() -> None:
    """What keeps the interpreter from exiting (a thread blocked in a session's close) does
    not keep the command from ending once its verb has returned."""
    import sys

    script = (
        "import threading, time\n"
        "from robomodel.runtime.transport import _zenoh_common\n"
        "from robomodel.cli import main\n"
        "threading.Thread(target=time.sleep, args=(120,)).start()  # not a daemon\n"
        "_zenoh_common.abandoned_sessions = 1\n"
        "main._exit_if_a_bus_hangs(7)\n"
    )
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, timeout=scaled(60))
    assert done.returncode == 7
