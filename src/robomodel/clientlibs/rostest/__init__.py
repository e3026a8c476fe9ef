"""rostest's Python entry points for a test node on robomodel: ``rostest.rosrun(package,
test_name, test)`` (the node is a rospy node) and ``rostest.unitrun`` (no node) run a
``unittest`` TestCase class or suite, print each test's result, and exit with status 1 when one
failed, as rostest's do. rostest writes a JUnit XML result under ``~/.ros/test_results``;
robomodel's prints the results only. ``import rostest`` gives this package when no real
rostest is on the path."""

from __future__ import annotations

import sys
import unittest
from collections.abc import Sequence
from typing import Any, NoReturn

__all__ = ["rosrun", "unitrun"]


def _suite(test: Any) -> unittest.TestSuite:
    if isinstance(test, unittest.TestSuite):
        return test
    if isinstance(test, type) and issubclass(test, unittest.TestCase):
        return unittest.TestLoader().loadTestsFromTestCase(test)
    raise TypeError(f"rostest needs a unittest.TestCase class or a TestSuite, got {test!r}")


def _run(package: str, test_name: str, test: Any) -> bool:
    print(f"[ROSTEST] {package}/{test_name}", flush=True)
    return unittest.TextTestRunner(stream=sys.stdout, verbosity=2).run(_suite(test)).wasSuccessful()


def rosrun(
    package: str, test_name: str, test: Any, sysargs: Sequence[str] | None = None
) -> NoReturn:
    """Run the tests of a rospy test node, shut its node down, and exit: status 0 if every
    test passed, else 1."""
    passed = _run(package, test_name, test)
    from robomodel.clientlibs.rospy import core

    core.signal_shutdown("test complete")
    sys.exit(0 if passed else 1)


def unitrun(
    package: str,
    test_name: str,
    test: Any,
    sysargs: Sequence[str] | None = None,
    coverage_packages: Sequence[str] | None = None,
) -> NoReturn:
    """Run the tests of a plain unit test (no node) and exit: status 0 if every test passed."""
    sys.exit(0 if _run(package, test_name, test) else 1)
