"""The ROS packages a user's node sees (``ament_index_python``, ``rospkg``, ``roslib``):
robomodel's package discovery (:class:`robomodel.description.packages.PackageIndex`) over
``--package-path`` (:func:`robomodel.runtime.msg._resolver.configure`), ``ROS_PACKAGE_PATH``,
``AMENT_PREFIX_PATH``, the working folder's workspace ``src/`` and the workspace around the
``__main__`` script."""

from __future__ import annotations

import os
import sys

from robomodel.description.packages import Package, PackageIndex

__all__ = ["find", "index"]


def index() -> PackageIndex:
    """The package index of this process's package path, as it is now (the environment is
    read on each call, as ament_index_python and rospkg read it)."""
    from robomodel.runtime.msg import _resolver

    found = PackageIndex(package_paths=_resolver.package_paths())
    if os.path.isdir("src"):
        source = os.path.abspath("src")
        found = found.with_fallback(source, label=f"the working folder's workspace {source}")
    script = getattr(sys.modules.get("__main__"), "__file__", None)
    return found.with_workspace_of(script) if script else found


def find(name: str) -> Package:
    """The package called ``name``; robomodel's PackageNotFoundError if none is."""
    return index().get(name)
