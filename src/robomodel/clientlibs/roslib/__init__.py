"""roslib's calls that ROS 1 node code still makes: ``load_manifest`` (the package must exist;
its ``src/`` folder joins ``sys.path`` as roslib adds it), and the modules
:mod:`.packages` and :mod:`.message`."""

from __future__ import annotations

import os
import sys

from robomodel.clientlibs.rospkg import RosPack

__all__ = ["load_manifest"]


def load_manifest(package_name: str, bootstrap_version: str = "0.7") -> None:
    """Check that ``package_name`` exists (rospkg.ResourceNotFound if not) and put its
    ``src/`` folder on ``sys.path``, as roslib's does for a package's Python code."""
    path = RosPack().get_path(package_name)
    source = os.path.join(path, "src")
    if os.path.isdir(source) and source not in sys.path:
        sys.path.insert(0, source)
