"""The wheel carries ``robomodel-clientlibs.pth`` at the top of site-packages: setup.py's
build_py copies it beside the packages and lists it among its outputs (run here in-process on
no packages, so nothing else is built)."""

from __future__ import annotations

import runpy
from pathlib import Path
from unittest import mock

import pytest
import setuptools
from setuptools.dist import Distribution

ROOT = Path(__file__).resolve().parents[2]


def test_build_py_puts_the_pth_file_beside_the_packages(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(ROOT)
    with mock.patch.object(setuptools, "setup"):
        namespace = runpy.run_path(str(ROOT / "setup.py"))
    command = namespace["BuildPyWithPth"](
        Distribution({"packages": [], "package_dir": {"": "src"}})
    )
    command.initialize_options()
    command.build_lib = str(tmp_path)
    command.finalize_options()
    command.run()
    built = tmp_path / "robomodel-clientlibs.pth"
    assert built.read_text() == (ROOT / "src" / "robomodel-clientlibs.pth").read_text()
    assert str(built) in command.get_outputs()
    assert "robomodel.clientlibs.hook" in built.read_text()
