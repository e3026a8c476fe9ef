"""rostest's ``unitrun`` (a plain unit test's exit status) and roslib's ``scriptutil`` name
resolution, in this process; ``rostest.rosrun`` in a node is run by test_debian_tools.py."""

from __future__ import annotations

import unittest

import pytest

from robomodel.clientlibs import rostest
from robomodel.clientlibs.roslib import scriptutil


class _Passes(unittest.TestCase):
    __test__ = False  # run by rostest.unitrun below, not collected by pytest

    def test_one(self) -> None:
        self.assertEqual(1 + 1, 2)


class _Fails(unittest.TestCase):
    __test__ = False

    def test_one(self) -> None:
        self.assertEqual(1 + 1, 3)


@pytest.mark.parametrize(("test", "status"), [(_Passes, 0), (_Fails, 1)])
def test_unitrun_exits_with_the_tests_status(test: type, status: int) -> None:
    with pytest.raises(SystemExit) as ended:
        rostest.unitrun("pkg", "unit", test)
    assert ended.value.code == status


def test_a_non_test_is_refused_naming_it() -> None:
    with pytest.raises(TypeError, match=r"unittest\.TestCase class or a TestSuite, got 42"):
        rostest.unitrun("pkg", "unit", 42)


@pytest.mark.parametrize(
    ("namespace", "name", "expected"),
    [
        ("", "chatter", "/chatter"),
        ("/robot", "chatter", "/robot/chatter"),
        ("robot/arm", "~rate", "/robot/arm/script/rate"),
        ("/robot", "/abs", "/abs"),
        ("/robot/", "", "/robot/"),
    ],
)
def test_script_resolve_name_as_roslib(
    monkeypatch: pytest.MonkeyPatch, namespace: str, name: str, expected: str
) -> None:
    monkeypatch.setenv("ROS_NAMESPACE", namespace)
    assert scriptutil.script_resolve_name("script", name) == expected


def test_the_master_proxies_are_not_offered() -> None:
    with pytest.raises(NotImplementedError, match="get_master"):
        scriptutil.get_master()
