"""Shared set-up of the ROS 1 launch tests: the corpus in a temporary workspace, Debian's
roslaunch as the reference, and the fake ``xacro`` package that runs the PyPI xacro 2.1.1."""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from tests.timing import scaled

CORPUS = Path(__file__).resolve().parent / "corpus"
ROSLAUNCH = "/usr/bin/roslaunch"


def reference_env(package_path: list[Path], home: Path) -> dict[str, str]:
    """The environment Debian's roslaunch runs in: its own Python, our package path."""
    env = {
        "PATH": "/usr/bin:/bin",
        "HOME": str(home),
        "ROS_PACKAGE_PATH": ":".join(str(p) for p in package_path),
        "ROS_MASTER_URI": "http://localhost:11311",
        "ROS_HOME": str(home / ".ros"),
        "LANG": "C.UTF-8",
    }
    return env


def roslaunch(args: list[str], env: dict[str, str], cwd: Path) -> subprocess.CompletedProcess[str]:
    if not Path(ROSLAUNCH).exists():
        pytest.fail(
            "Debian's roslaunch is missing: apt-get install python3-roslaunch (make test does)"
        )
    return subprocess.run(
        [ROSLAUNCH, *args], capture_output=True, text=True, env=env, cwd=cwd, timeout=scaled(120)
    )


def roslaunch_many(
    calls: list[list[str]], env: dict[str, str], cwd: Path
) -> list[subprocess.CompletedProcess[str]]:
    """What :func:`roslaunch` gives for each of ``calls`` (query modes: ``--dump-params``,
    ``--nodes``, ``--args``, ``--files``, ``--ros-args``), run by ``roslaunch.main`` in one
    process of Debian's Python (roslaunch_batch.py) instead of one ``/usr/bin/roslaunch`` each."""
    if not Path(ROSLAUNCH).exists():
        pytest.fail(
            "Debian's roslaunch is missing: apt-get install python3-roslaunch (make test does)"
        )
    batch = subprocess.run(
        ["/usr/bin/python3", str(Path(__file__).with_name("roslaunch_batch.py"))],
        input=json.dumps(calls), capture_output=True, text=True, env=env, cwd=cwd,
        timeout=scaled(60 + 60 * len(calls)),
    )  # fmt: skip
    assert batch.returncode == 0, batch.stderr
    return [
        subprocess.CompletedProcess([ROSLAUNCH, *argv], code, out, err)
        for argv, (code, out, err) in zip(calls, json.loads(batch.stdout), strict=True)
    ]


# xacro 2.1.1 resolves $(find pkg) with ament_index_python, which ROS 1 does not have: the
# reference script gets a minimal one that finds packages on ROS_PACKAGE_PATH as rospack does
# (the directory of the first package.xml with that <name>), so that roslaunch's xacro commands
# of the examples ($(find rrbot_description)) run under Debian's roslaunch.
_AMENT_INDEX_FROM_ROS_PACKAGE_PATH = """
import os, re, sys, types

def _share(name):
    for root in os.environ.get("ROS_PACKAGE_PATH", "").split(os.pathsep):
        for folder, dirs, files in os.walk(root):
            if "package.xml" in files:
                dirs[:] = []
                text = open(os.path.join(folder, "package.xml"), encoding="utf-8").read()
                found = re.search(r"<name>\\s*([^<\\s]+)\\s*</name>", text)
                if found and found.group(1) == name:
                    return folder
    raise _NotFound(name)

class _NotFound(KeyError):
    pass

_packages = types.ModuleType("ament_index_python.packages")
_packages.get_package_share_directory = _share
_packages.PackageNotFoundError = _NotFound
_root = types.ModuleType("ament_index_python")
_root.packages = _packages
_root.get_package_share_directory = _share
_root.PackageNotFoundError = _NotFound
sys.modules["ament_index_python"] = _root
sys.modules["ament_index_python.packages"] = _packages
"""


@pytest.fixture
def workspace(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """The corpus copied to a temporary workspace, plus a ``xacro`` package whose scripts run
    the reference xacro 2.1.1 (PyPI), for Debian's roslaunch to call."""
    ws = tmp_path / "ws"
    shutil.copytree(CORPUS, ws)
    xacro = ws / "xacro"
    xacro.mkdir()
    (xacro / "package.xml").write_text("<package format='2'><name>xacro</name></package>")
    for name in ("xacro", "xacro.py"):
        script = xacro / name
        script.write_text(
            f"#!{sys.executable} -I\n"  # -I: the script's folder (with xacro.py) is not on sys.path
            + _AMENT_INDEX_FROM_ROS_PACKAGE_PATH
            + "import xacro\nsys.exit(xacro.main())\n"
        )
        script.chmod(0o755)
    (tmp_path / "home").mkdir()
    # for the reference roslaunch's in-process parts; undone after the test, as robomodel's
    # verbs pick the ROS 1 bus when ROS_MASTER_URI is set
    monkeypatch.setenv("ROS_MASTER_URI", "http://localhost:11311")
    return ws
