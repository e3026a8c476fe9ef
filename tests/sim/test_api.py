"""Public names of robomodel.sim resolve; MuJoCo is imported only when a simulation is built."""

from __future__ import annotations

import subprocess
import sys

import robomodel.sim as sim


def test_all_names_resolve() -> None:
    for name in sim.__all__:
        assert getattr(sim, name) is not None, name


def test_importing_the_package_does_not_import_mujoco() -> None:
    code = "import sys, robomodel.sim; print('mujoco' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"
