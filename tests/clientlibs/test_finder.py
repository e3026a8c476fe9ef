"""The import finder in process: what a failed import of another name costs it."""

from __future__ import annotations

import sys

import pytest

from robomodel.clientlibs import finder


def test_an_unknown_name_without_rosbags_installed_is_not_found_without_recursion(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """pip's isolated build environments have robomodel's finder (the .pth) but no rosbags:
    looking for rosbags must not ask the finder again."""
    for name in [n for n in sys.modules if n == "rosbags" or n.startswith("rosbags.")]:
        monkeypatch.delitem(sys.modules, name)
    monkeypatch.setattr(sys, "path", [])
    monkeypatch.setattr(finder, "_store_texts", [])
    monkeypatch.delenv("ROS_PACKAGE_PATH", raising=False)
    monkeypatch.delenv("AMENT_PREFIX_PATH", raising=False)
    monkeypatch.chdir("/")
    assert finder.ClientLibraryFinder().find_spec("no_such_module_here", None) is None
    assert finder._store_texts == []
