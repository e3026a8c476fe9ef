"""A real rclpy on the path (a sourced ROS 2 install) is the one imported, its submodules too:
robomodel's finder only serves ``rclpy`` and ``rclpy.*`` when Python's own finders find none."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

PROBE = (
    "import rclpy, rclpy.node, rclpy.executors; "
    "print(rclpy.__file__); print(rclpy.node.__file__); print(rclpy.executors.__name__)"
)


def _probe(pythonpath: str) -> list[str]:
    env = {**os.environ, "PYTHONPATH": pythonpath}
    run = subprocess.run([sys.executable, "-c", PROBE], capture_output=True, text=True, env=env)
    assert run.returncode == 0, run.stderr
    return run.stdout.splitlines()


def test_a_fake_rclpy_on_pythonpath_is_the_one_imported(tmp_path: Path) -> None:
    fake = tmp_path / "rclpy"
    fake.mkdir()
    (fake / "__init__.py").write_text("")
    (fake / "node.py").write_text("")
    (fake / "executors.py").write_text("")
    ours = os.environ.get("PYTHONPATH", "")
    init, node, executors = _probe(os.pathsep.join(p for p in (str(tmp_path), ours) if p))
    assert init == str(fake / "__init__.py")
    assert node == str(fake / "node.py")
    assert executors == "rclpy.executors"
    init, node, executors = _probe(ours)  # without it, robomodel's
    assert init.endswith("robomodel/clientlibs/rclpy/__init__.py")
    assert node.endswith("robomodel/clientlibs/rclpy/node.py")
    assert executors == "robomodel.clientlibs.rclpy.executors"  # one module, robomodel's name
