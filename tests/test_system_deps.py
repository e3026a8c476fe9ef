"""tools/system-deps names what the README's commands need before make creates .venv."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

from tests.docs.runner import ROOT

SCRIPT = ROOT / "tools" / "system-deps"


def _run(want: str, tmp_path: Path, python: str) -> subprocess.CompletedProcess[str]:
    """The script on a PATH with no apt-get, no dot and no sudo: it can only name packages."""
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir(exist_ok=True)
    for tool in ("bash", "sort", "id"):
        found = shutil.which(tool)
        assert found is not None, tool
        (bin_dir / tool).symlink_to(found)
    env = {"PATH": str(bin_dir), "PYTHON": python, "HOME": os.environ.get("HOME", "/")}
    return subprocess.run(
        [str(bin_dir / "bash"), str(SCRIPT), want], capture_output=True, text=True, env=env
    )


def test_demo_needs_graphviz_and_a_python_that_makes_venvs(tmp_path: Path) -> None:
    no_venv = tmp_path / "python3"
    # a Python whose ensurepip is missing, as Debian's and Ubuntu's without python3-venv
    no_venv.write_text("#!/bin/sh\nexit 1\n")
    no_venv.chmod(0o755)
    done = _run("demo", tmp_path, str(no_venv))
    assert done.returncode == 1
    assert done.stderr.strip() == (
        "robomodel: missing system packages for 'make demo': graphviz python3-venv "
        "(Debian/Ubuntu: sudo apt-get install graphviz python3-venv)"
    )


def test_a_python_with_venv_is_not_named(tmp_path: Path) -> None:
    done = _run("demo", tmp_path, sys.executable)
    assert "python3-venv" not in done.stderr and "graphviz" in done.stderr
