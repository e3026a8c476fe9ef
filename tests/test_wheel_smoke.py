"""The built wheel under every Python the package claims (3.10-3.13) that this machine has:
tools/wheel_smoke.py installs it (not editable) into a fresh venv per interpreter and runs one
command of each verb family outside the checkout. tests/conftest.py starts this test first, so
that it runs beside the rest of the suite rather than after it."""

from __future__ import annotations

import importlib.util
import re
import subprocess
import sys
import warnings
from types import ModuleType

from tests.conftest import ROOT, unique_domain
from tests.timing import scaled

SMOKE = ROOT / "tools" / "wheel_smoke.py"


def _tool() -> ModuleType:
    spec = importlib.util.spec_from_file_location("wheel_smoke", SMOKE)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module  # dataclasses look their module up while being made
    spec.loader.exec_module(module)
    return module


def test_the_wheel_runs_each_verb_family_under_every_claimed_python() -> None:
    wheel_smoke = _tool()
    domains = [unique_domain() for _ in wheel_smoke.CLAIMED]
    done = subprocess.run(
        [sys.executable, str(SMOKE), "--domain-ids", *domains],
        capture_output=True, text=True, timeout=scaled(900),
    )  # fmt: skip
    missing = [line for line in done.stderr.splitlines() if "on this machine" in line]
    if missing:
        warnings.warn(missing[0], stacklevel=1)
    # first the lines naming each failed step: "Python 3.12 (...): sim FAILED: `...` exited 1:"
    failed = [
        line
        for line in done.stderr.splitlines()
        if re.search(r"\): \S+ FAILED: |the wheel FAILED", line)
    ]
    assert done.returncode == 0, "\n".join([*failed, "", done.stdout, done.stderr])
    # every interpreter found ran every family (a smoke that skipped one would pass silently)
    passed = [line for line in done.stdout.splitlines() if ": passed in " in line]
    assert len(passed) == len(wheel_smoke.find_pythons()) >= 1, done.stdout
    for line in passed:
        for family in ("import", "check", "xacro", "fk", "sim", "new+launch"):
            assert f"{family} " in line, line
