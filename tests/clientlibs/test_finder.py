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


def test_robomodels_own_types_are_known_without_rosbags(monkeypatch: pytest.MonkeyPatch) -> None:
    """The ``bus`` and ``sim`` extras bring no rosbags: the interface modules still list
    robomodel's own types (``from std_msgs.msg import String`` in a venv of the wheel), and
    leave out only the names of rosbags' stores."""
    import functools

    from robomodel.clientlibs import interfaces
    from robomodel.runtime.msg import _resolver

    for name in [n for n in sys.modules if n == "rosbags" or n.startswith("rosbags.")]:
        monkeypatch.delitem(sys.modules, name)
    monkeypatch.setitem(sys.modules, "rosbags", None)  # `import rosbags...` raises ImportError
    monkeypatch.setattr(_resolver, "_store", functools.cache(_resolver._store.__wrapped__))
    names = interfaces._type_names_of.__wrapped__(-1)
    assert {"std_msgs/msg/String", "sensor_msgs/msg/JointState"} <= names
    # in rosbags' Noetic store only: known with rosbags, not without
    assert "actionlib/msg/TestGoal" not in _resolver.definition_names()
    monkeypatch.undo()
    assert "actionlib/msg/TestGoal" in _resolver.definition_names()
