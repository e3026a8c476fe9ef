"""The packages of the working folder's workspace ``src/``, found with a few directory scans
and the standard library alone: the import finder asks at every failed import."""

from __future__ import annotations

import os

__all__ = ["src_folders"]


def src_folders() -> list[str]:
    """The folders with a ``package.xml`` at ``src/<name>`` or ``src/<group>/<name>`` of the
    working folder (a colcon or catkin workspace's layout), read with a few directory scans."""
    if not os.path.isdir("src"):
        return []
    found = []
    with os.scandir("src") as entries:
        folders = [e.path for e in entries if e.is_dir() and not e.name.startswith(".")]
    for folder in folders:
        if os.path.isfile(os.path.join(folder, "package.xml")):
            found.append(os.path.abspath(folder))
            continue
        with os.scandir(folder) as inner:
            found += [
                os.path.abspath(e.path)
                for e in inner
                if e.is_dir() and os.path.isfile(os.path.join(e.path, "package.xml"))
            ]
    return found
