"""The import hook that makes ``launch``, ``launch_ros``, ``ament_index_python`` and ``xacro``
importable while (and only while) a launch file is loaded.

A ``sys.meta_path`` finder is inserted first for the duration of :func:`launch_modules`; the
modules it creates are removed from ``sys.modules`` afterwards and any real module of the same
name is put back, so a real ROS install or the pip ``xacro`` is never shadowed outside a load.
A name robomodel lacks fails with a LaunchError naming it and the launch file line.
"""

from __future__ import annotations

import importlib
import importlib.abc
import importlib.machinery
import sys
import types
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from typing import Any

from robomodel.launch.model import LaunchError
from robomodel.launch.ros2.shim.context import caller_location, current_session
from robomodel.launch.ros2.shim.modules import MODULES

__all__ = ["ROOTS", "launch_modules"]

ROOTS = frozenset(name.split(".")[0] for name in MODULES)


def _missing(what: str) -> LaunchError:
    session = current_session()
    stack = tuple(session.include_stack) if session is not None else ()
    return LaunchError(
        f"{what} is not supported by robomodel launch (see the README's ROS 2 launch section "
        "for what is)",
        location=caller_location(3),
        include_stack=stack,
    )


def _make_module(fullname: str) -> types.ModuleType:
    module = types.ModuleType(fullname)
    names = MODULES[fullname]()
    module.__dict__.update(names)
    module.__all__ = sorted(n for n in names if not n.startswith("_"))  # type: ignore[attr-defined]
    module.__path__ = []  # every shim module may have submodules
    module.__robomodel_shim__ = True  # type: ignore[attr-defined]

    def __getattr__(name: str) -> Any:
        if name.startswith("__"):
            raise AttributeError(name)
        if f"{fullname}.{name}" in MODULES:
            return importlib.import_module(f"{fullname}.{name}")
        raise _missing(f"'{fullname}.{name}'")

    module.__getattr__ = __getattr__  # type: ignore[method-assign]
    return module


class _Loader(importlib.abc.Loader):
    def create_module(self, spec: importlib.machinery.ModuleSpec) -> types.ModuleType:
        return _make_module(spec.name)

    def exec_module(self, module: types.ModuleType) -> None:
        return None


class _Finder(importlib.abc.MetaPathFinder):
    def find_spec(
        self, fullname: str, path: Sequence[str] | None, target: types.ModuleType | None = None
    ) -> importlib.machinery.ModuleSpec | None:
        if fullname.split(".")[0] not in ROOTS:
            return None
        if fullname not in MODULES:
            raise _missing(f"module '{fullname}'")
        return importlib.machinery.ModuleSpec(fullname, _Loader(), is_package=True)


def _ours(name: str) -> bool:
    return name.split(".")[0] in ROOTS


@contextmanager
def launch_modules() -> Iterator[None]:
    """Provide the shim modules for the duration of the ``with`` block."""
    saved = {name: module for name, module in sys.modules.items() if _ours(name)}
    for name in saved:
        del sys.modules[name]
    finder = _Finder()
    sys.meta_path.insert(0, finder)
    try:
        yield
    finally:
        sys.meta_path.remove(finder)
        for name in [n for n in sys.modules if _ours(n)]:
            del sys.modules[name]
        sys.modules.update(saved)
