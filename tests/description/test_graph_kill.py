"""A killed ``robomodel graph -o out.svg`` leaves no file behind.

dot used to write its own temporary file beside the target and, killed with its parent gone,
finished it anyway: ``.out.svg.<random>.svg`` piled up. Now dot writes to a pipe, dies with
robomodel (PR_SET_PDEATHSIG), and SIGTERM runs the cleanup.
"""

from __future__ import annotations

import os
import signal
import subprocess
import time
from pathlib import Path

import pytest

from tests.conftest import ROBOMODEL
from tests.timing import scaled


def _chain(path: Path, links: int) -> None:
    joints = "".join(
        f'<link name="l{i}"/><joint name="j{i}" type="fixed"><parent link="l{i - 1}"/>'
        f'<child link="l{i}"/></joint>'
        for i in range(1, links)
    )
    path.write_text(f'<robot name="c"><link name="l0"/>{joints}</robot>')


def _dot_children_of(pid: int) -> list[int]:
    found = []
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            stat = (entry / "stat").read_text()
            cmdline = (entry / "cmdline").read_bytes()
        except OSError:
            continue
        ppid = int(stat.rsplit(")", 1)[1].split()[1])
        if ppid == pid and cmdline.startswith(b"/") and b"dot" in cmdline.split(b"\0")[0]:
            found.append(int(entry.name))
    return found


@pytest.mark.parametrize("sig", [signal.SIGKILL, signal.SIGTERM])
def test_killed_graph_leaves_no_temporary_file(tmp_path: Path, sig: signal.Signals) -> None:
    model = tmp_path / "chain.urdf"
    _chain(model, 1500)
    out = tmp_path / "out" / "graph.svg"
    out.parent.mkdir()
    for _ in range(3):
        proc = subprocess.Popen([*ROBOMODEL, "graph", str(model), "-o", str(out)])
        deadline = time.monotonic() + scaled(60)
        while not _dot_children_of(proc.pid) and time.monotonic() < deadline:
            if proc.poll() is not None:
                pytest.fail("graph ended before dot started")
            time.sleep(0.01)
        dots = _dot_children_of(proc.pid)
        assert dots, "dot never started"
        os.kill(proc.pid, sig)
        proc.wait(timeout=scaled(30))
        # dot must not outlive robomodel: it would finish and write its output.
        deadline = time.monotonic() + scaled(10)
        while any(Path(f"/proc/{d}").exists() for d in dots) and time.monotonic() < deadline:
            time.sleep(0.05)
        assert not any(Path(f"/proc/{d}/cmdline").exists() for d in dots)
    assert list(out.parent.iterdir()) == []


def test_graph_still_renders(tmp_path: Path) -> None:
    model = tmp_path / "chain.urdf"
    _chain(model, 5)
    out = tmp_path / "graph.svg"
    run = subprocess.run([*ROBOMODEL, "graph", str(model), "-o", str(out)], capture_output=True)
    assert run.returncode == 0, run.stderr
    assert out.read_bytes().lstrip().startswith(b"<?xml") and b"l4" in out.read_bytes()
    assert {p.name for p in tmp_path.iterdir()} == {"chain.urdf", "graph.svg"}
