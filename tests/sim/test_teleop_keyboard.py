"""A keyboard teleop node of the user's own package, written against rclpy in the style of
teleop_twist_keyboard and started with ``robomodel run`` in a terminal (tmux), drives the
simplebot of ``robomodel sim``: the keys reach the node through the terminal robomodel hands
it, and its Twist reaches the diff-drive controller over Zenoh."""

from __future__ import annotations

import os
import shlex
import shutil
import subprocess
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
import yaml

from tests.conftest import ROBOMODEL, end_process, unique_domain
from tests.timing import scaled, wait_until

from .conftest import SIMPLEBOT, SIMPLEBOT_YAML

WS = Path(__file__).resolve().parents[1] / "launch" / "user_ws" / "src"

pytestmark = pytest.mark.skipif(shutil.which("tmux") is None, reason="needs tmux")


@pytest.fixture(scope="module")
def sim() -> Iterator[str]:
    """One simplebot simulation for the module, on a Zenoh domain of its own."""
    domain = unique_domain()
    proc = subprocess.Popen(
        [*ROBOMODEL, "sim", str(SIMPLEBOT), "--controllers", str(SIMPLEBOT_YAML), "--headless",
         "--domain-id", domain],
        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
    )  # fmt: skip
    try:
        wait_until(lambda: _position(domain) is not None, scaled(60), what="the simulation")
        yield domain
    finally:
        end_process(proc, timeout_s=20)


def _position(domain: str) -> tuple[float, float] | None:
    """The simplebot's ground-truth x, y [m], as ``robomodel topic echo --once`` prints it."""
    echo = subprocess.run(
        [*ROBOMODEL, "topic", "echo", "/ground_truth/odom", "--once", "--domain-id", domain],
        capture_output=True, text=True, timeout=scaled(30),
    )  # fmt: skip
    if echo.returncode != 0:
        return None
    position = yaml.safe_load(echo.stdout.split("\n---")[0])["pose"]["pose"]["position"]
    return float(position["x"]), float(position["y"])


class Tmux:
    """A tmux server of the test's own (``-S`` socket), one window."""

    def __init__(self, socket: Path) -> None:
        self.socket = socket

    def __call__(self, *argv: str) -> str:
        done = subprocess.run(
            ["tmux", "-S", str(self.socket), *argv], capture_output=True, text=True, check=True
        )
        return done.stdout

    def screen(self) -> str:
        return self("capture-pane", "-p", "-t", "teleop")


def test_keyboard_teleop_drives_the_simplebot(sim: str, tmp_path: Path) -> None:
    tmux = Tmux(tmp_path / "tmux.sock")
    env = {
        "PATH": os.environ["PATH"],
        "PYTHONPATH": os.environ.get("PYTHONPATH", ""),
        "HOME": os.environ.get("HOME", str(tmp_path)),
        "ROS_DOMAIN_ID": sim,
    }
    command = shlex.join(
        [*ROBOMODEL, "run", "--package-path", str(WS), "teleop_keys", "teleop_keyboard",
         "--ros-args", "-r", "cmd_vel:=/simplebot_controller/cmd_vel", "-p", "speed:=0.4"]
    )  # fmt: skip
    exports = " ".join(f"{k}={shlex.quote(v)}" for k, v in env.items())
    tmux("new-session", "-d", "-s", "teleop", "-x", "100", "-y", "30",
         f"env {exports} {command}; echo teleop-exited-$?; sleep 600")  # fmt: skip
    try:
        wait_until(lambda: "Reading from the keyboard" in tmux.screen(), scaled(60),
                   what=lambda: f"the teleop's help:\n{tmux.screen()}")  # fmt: skip
        start = _position(sim)
        assert start is not None
        tmux("send-keys", "-t", "teleop", "i")
        wait_until(lambda: "x 0.40" in tmux.screen(),
                   scaled(10), what=lambda: f"the key read:\n{tmux.screen()}")  # fmt: skip

        def moved() -> Any:
            now = _position(sim)
            return now is not None and now[0] - start[0] > 0.3

        wait_until(moved, scaled(30), what=lambda: f"the robot driving forward from {start}")
        tmux("send-keys", "-t", "teleop", "k")  # stop
        tmux("send-keys", "-t", "teleop", "q")
        wait_until(lambda: "teleop-exited-0" in tmux.screen(), scaled(20),
                   what=lambda: f"the teleop ending with 0:\n{tmux.screen()}")  # fmt: skip
        stopped = _position(sim)
        assert stopped is not None
        after = _position(sim)
        assert after is not None and abs(after[0] - stopped[0]) < 0.05  # it stays stopped
    finally:
        subprocess.run(["tmux", "-S", str(tmp_path / "tmux.sock"), "kill-server"],
                       capture_output=True, check=False)  # fmt: skip
