"""Debian's rviz in a virtual screen, for the tests that look at what it draws."""

from __future__ import annotations

import os
import subprocess
import time
from collections.abc import Callable
from pathlib import Path

from tests.ros1wire.conftest import Ros1
from tests.timing import scaled

# starts of rviz that a crash at start may take before the test fails
RVIZ_STARTS = 3


def xvfb(ros1: Ros1, size: str) -> str:
    """A virtual screen on a display number Xvfb chooses itself (``-displayfd``): a number of
    our own choosing could be one another test's Xvfb already holds."""
    read, write = os.pipe()
    proc = subprocess.Popen(
        ["Xvfb", "-displayfd", str(write), "-screen", "0", size, "-nolisten", "tcp"],
        pass_fds=(write,), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
        start_new_session=True,
    )  # fmt: skip
    os.close(write)
    ros1.procs.append(proc)
    with os.fdopen(read) as numbers:
        number = numbers.readline().strip()  # written once the screen accepts clients
    assert number.isdigit(), "Xvfb did not start"
    return f":{number}"


def rviz_until(
    ros1: Ros1,
    config: Path,
    display: str,
    log: Path,
    done: Callable[[Path], bool],
    timeout_s: float,
) -> Path:
    """Start Debian's ``rviz -d config`` on ``display`` and grab its screen once a second until
    ``done`` (given the screenshot) says yes or ``timeout_s`` (scaled) passed; the last
    screenshot.

    Debian's rviz 1.14 has been seen to die by a signal at start on a loaded machine, before
    it drew a frame: glibc's ``free(): invalid next size`` (SIGABRT), and a SIGSEGV right after
    "Forcing OpenGl version 0" (OGRE's software GL). Such a start is tried again, up to
    :data:`RVIZ_STARTS` starts; rviz ending any other way, or a last start dying, fails the
    test with its log."""
    from PIL import ImageGrab

    shot = log.with_suffix(".png")
    for start in range(1, RVIZ_STARTS + 1):
        with log.open("w") as out:
            rviz = subprocess.Popen(
                ["/usr/bin/rviz", "-d", str(config)],
                env={**ros1.env, "DISPLAY": display, "LIBGL_ALWAYS_SOFTWARE": "1"},
                stdout=out, stderr=subprocess.STDOUT, start_new_session=True,
            )  # fmt: skip
        ros1.procs.append(rviz)  # type: ignore[arg-type]
        deadline = time.monotonic() + scaled(timeout_s)
        while rviz.poll() is None:
            ImageGrab.grab(xdisplay=display).save(shot)
            if done(shot) or time.monotonic() > deadline:
                return shot
            time.sleep(1.0)
        text = log.read_text()
        assert rviz.returncode < 0 and start < RVIZ_STARTS, (
            f"rviz ended ({rviz.returncode}): {text}"
        )
        print(f"rviz died by signal {-rviz.returncode} (start {start}); started again:\n{text}")
    raise AssertionError("unreachable")
