"""The README's quickstart, typed as written: every line of its block runs.

Commands that end (check, xacro, fk) must exit 0; the ones that keep running (launch) must reach
"N nodes running" and end cleanly on Ctrl-C, as a user sees them do.
"""

from __future__ import annotations

import os
import re
import shlex
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from tests.conftest import ROOT, unique_domain
from tests.docs.runner import commands
from tests.timing import scaled

_MARKER = "<!-- quickstart: tests/test_readme_quickstart.py runs each line -->"
_BIN = Path(sys.executable).parent  # the venv the README tells the user to activate


def _quickstart_blocks() -> list[str]:
    """The README's blocks marked as quickstart (the five commands, one per lesson)."""
    parts = (ROOT / "README.md").read_text().split(_MARKER)[1:]
    return [part.split("```bash\n", 1)[1].split("```", 1)[0] for part in parts]


def _quickstart_lines() -> list[str]:
    return [line for block in _quickstart_blocks() for line in commands(block)]


def _robomodel_commands() -> list[str]:
    return [line for line in _quickstart_lines() if line.startswith("robomodel ")]


def test_quickstart_sets_up_the_command_and_the_packages() -> None:
    quickstart, per_lesson = _quickstart_blocks()
    lines = commands(quickstart)
    assert len(lines) == 5  # a five-command quickstart
    assert lines[0] == "source .venv/bin/activate"
    assert lines[1] == "export ROS_PACKAGE_PATH=$PWD/examples"
    assert lines[-1] == "robomodel topic list"
    assert (_BIN / "robomodel").exists(), "make demo/test installs the robomodel command"
    # then one command per lesson of the course, each named in its comment
    lessons = set(re.findall(r"# ([^:\n]+):", per_lesson))
    assert lessons == {
        "URDF gripper",
        "UR5 in simulation",
        "simplebot lab",
        "ROS 2 two-link arm",
        "example_description",
    }


@pytest.fixture
def workdir(tmp_path: Path) -> Path:
    (tmp_path / "examples").symlink_to(ROOT / "examples")
    return tmp_path


def _env(workdir: Path) -> dict[str, str]:
    env = dict(os.environ)
    env["PATH"] = f"{_BIN}{os.pathsep}{env.get('PATH', '')}"
    env["ROS_PACKAGE_PATH"] = str(workdir / "examples")
    env["ROS_DOMAIN_ID"] = unique_domain()
    env["ROBOMODEL_VIEWER_PORT"] = "0"  # any free port: other tests' viewers run beside
    env.pop("ROS_MASTER_URI", None)
    return env


def _run_until_running(argv: list[str], workdir: Path, timeout_s: float) -> None:
    proc = subprocess.Popen(
        argv,
        cwd=workdir,
        env=_env(workdir),
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
        start_new_session=True,
    )
    seen: list[str] = []
    deadline = time.monotonic() + timeout_s
    try:
        assert proc.stdout is not None
        for line in proc.stdout:
            seen.append(line)
            if re.search(r"\d+ nodes? running", line) or time.monotonic() > deadline:
                break
        assert any(re.search(r"\d+ nodes? running", s) for s in seen), "".join(seen)
        assert not any("Traceback" in s for s in seen), "".join(seen)
        os.killpg(proc.pid, signal.SIGINT)
        rest, _ = proc.communicate(timeout=scaled(60))
        # 0 once the launch's loop runs; 130 (Ctrl-C) when it comes during start-up
        assert proc.returncode in (0, 130), "".join(seen) + rest
        assert "Traceback" not in rest, rest
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()


def _first_launch() -> str:
    return next(c for c in _robomodel_commands() if c.split()[1] == "launch")


def _topic_list_beside_a_launch(argv: list[str], workdir: Path) -> None:
    """``topic list`` in a second terminal while the quickstart's first launch runs; that
    launch is held to what :func:`_run_until_running` asks of the others (it runs once)."""
    first = shlex.split(_first_launch())
    env = _env(workdir)
    launch = subprocess.Popen(
        first, cwd=workdir, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
        text=True, start_new_session=True,
    )  # fmt: skip
    seen: list[str] = []
    try:
        assert launch.stdout is not None
        for line in launch.stdout:
            seen.append(line)
            if re.search(r"\d+ nodes? running", line):
                break
        assert any(re.search(r"\d+ nodes? running", s) for s in seen), "".join(seen)
        assert not any("Traceback" in s for s in seen), "".join(seen)
        listed = subprocess.run(
            argv, cwd=workdir, env=env, capture_output=True, text=True, timeout=scaled(120)
        )
        assert listed.returncode == 0, listed.stderr
        assert {"/joint_states", "/tf", "/robot_description"} <= set(listed.stdout.split())
        os.killpg(launch.pid, signal.SIGINT)
        rest, _ = launch.communicate(timeout=scaled(60))
        # 0 once the launch's loop runs; 130 (Ctrl-C) when it comes during start-up
        assert launch.returncode in (0, 130), "".join(seen) + rest
        assert "Traceback" not in rest, rest
    finally:
        if launch.poll() is None:
            os.killpg(launch.pid, signal.SIGKILL)
            launch.wait()


# the first launch runs in the topic list's test, beside it (the same command, held to the same)
@pytest.mark.parametrize("command", [c for c in _robomodel_commands() if c != _first_launch()])
def test_quickstart_command_runs(command: str, workdir: Path) -> None:
    argv = shlex.split(command)
    if argv[1] == "launch":
        _run_until_running(argv, workdir, timeout_s=scaled(120))
        return
    if argv[1:3] == ["topic", "list"]:  # "in a second terminal while a launch runs"
        _topic_list_beside_a_launch(argv, workdir)
        return
    done = subprocess.run(
        argv, cwd=workdir, env=_env(workdir), capture_output=True, text=True, timeout=scaled(120)
    )
    assert done.returncode == 0, done.stderr
    if argv[1] == "check":
        assert "robot name is: planar_3dof" in done.stdout
    if argv[1] == "xacro":
        assert "<robot" in (workdir / "planar_3dof.urdf").read_text()
    if argv[1] == "fk":
        assert re.search(r"^ee_link\s+xyz", done.stdout, flags=re.M), done.stdout
