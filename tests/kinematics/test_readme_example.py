"""The kinematics reference's example (docs/reference/kinematics.md) runs as written, from the checkout's root
(it once named ``tool0``, a link the example UR5 does not have)."""

from __future__ import annotations

import re

import numpy as np
import pytest

from tests.conftest import ROOT


def _kinematics_block() -> str:
    section = (ROOT / "docs/reference/kinematics.md").read_text(encoding="utf-8")
    found = re.search(r"```python\n(.*?)```", section, re.S)
    assert found is not None
    return found.group(1)


def test_the_readme_kinematics_example_runs(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(ROOT)
    code = _kinematics_block()
    assert "tool0" not in code
    scope: dict[str, object] = {}
    exec(compile(code, "docs/reference/kinematics.md", "exec"), scope)
    kin = scope["kin"]
    solutions = np.asarray(scope["solutions"])
    assert solutions.ndim == 2 and solutions.shape[1] == 6 and 1 <= len(solutions) <= 8
    assert scope["result"].success  # type: ignore[attr-defined]
    # the analytic solutions all reach one pose
    poses = np.array([kin.fk_link(q, "ee_link") for q in solutions])  # type: ignore[attr-defined]
    np.testing.assert_allclose(poses, np.broadcast_to(poses[0], poses.shape), atol=1e-6)
