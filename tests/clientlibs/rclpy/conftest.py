"""Fixtures of the rclpy tests: the tests' own interface package on the package path, and an
initialised rclpy (in-process bus: the nodes talk through robomodel's in-process transport)."""

from __future__ import annotations

import os
from collections.abc import Iterator
from pathlib import Path

import pytest

INTERFACES = Path(__file__).with_name("interfaces")


def _package_path(*paths: Path) -> None:
    """The resolver's package path (``--package-path``), and the finder's memory of the
    interface packages forgotten so that it looks again."""
    from robomodel.clientlibs import interfaces
    from robomodel.runtime.msg import _resolver

    _resolver.configure(package_paths=paths)
    forget = getattr(interfaces._all_type_names, "cache_clear", None)
    if forget is not None:
        forget()


@pytest.fixture(scope="module")
def tutorial_interfaces() -> Iterator[Path]:
    """``tutorial_interfaces`` (Num, AddTwoInts, Fibonacci) importable as a user's package,
    for one module: the processes other modules' tests start inherit no package path."""
    before = os.environ.get("ROS_PACKAGE_PATH")
    os.environ["ROS_PACKAGE_PATH"] = os.pathsep.join(p for p in (str(INTERFACES), before) if p)
    _package_path(INTERFACES)
    yield INTERFACES
    if before is None:
        os.environ.pop("ROS_PACKAGE_PATH", None)
    else:
        os.environ["ROS_PACKAGE_PATH"] = before
    _package_path()


@pytest.fixture
def rclpy_inproc(tutorial_interfaces: Path) -> Iterator[None]:
    """``rclpy.init()`` on the in-process bus; shut down after the test."""
    import rclpy

    rclpy.init(args=["test"], bus="inproc")
    yield
    rclpy.try_shutdown()
