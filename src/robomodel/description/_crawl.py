"""rospack's crawl and ament's package markers, on strings with ``os`` alone.

:class:`robomodel.description.packages.PackageIndex` finds packages with these, and so does the
client-library finder, which runs in every Python process of the environment when an import
fails and must not pay for ``pathlib``, ``re`` or ``dataclasses`` there.

A scanned directory that holds a ``package.xml`` is a package: its name is the manifest's
``<name>`` (the folder's name when it has none) and the scan does not descend further.
Directories holding ``CATKIN_IGNORE``, ``COLCON_IGNORE`` or ``AMENT_IGNORE`` and hidden
directories are skipped.
"""

from __future__ import annotations

import os

__all__ = [
    "IGNORE_MARKERS",
    "MAX_SCAN_DEPTH",
    "ament_packages",
    "manifest_name",
    "scan_tree",
    "split_paths",
]

IGNORE_MARKERS = ("CATKIN_IGNORE", "COLCON_IGNORE", "AMENT_IGNORE")
MAX_SCAN_DEPTH = 12
_AMENT_MARKERS = os.path.join("share", "ament_index", "resource_index", "packages")
_MANIFEST_HEAD_BYTES = 65536  # <name> comes first in a manifest


def _name_in(head: bytes) -> str | None:
    """The first ``<name>NAME</name>`` of ``head`` whose NAME is one word with no ``<``, with
    any white space around it: ``re.search(rb"<name>\\s*([^<\\s]+)\\s*</name>")``."""
    start = head.find(b"<name>")
    while start >= 0:
        body = start + len(b"<name>")
        close = head.find(b"<", body)
        if close >= 0 and head.startswith(b"</name>", close):
            words = head[body:close].split()
            if len(words) == 1:
                return words[0].decode("utf-8", "replace")
        start = head.find(b"<name>", body)
    return None


def manifest_name(manifest: str) -> str | None:
    """The ``<name>`` of the ``package.xml`` at ``manifest``, or None (not a readable file, no
    name)."""
    if not os.path.isfile(manifest):  # a device or a FIFO named package.xml is not read
        return None
    try:
        with open(manifest, "rb") as handle:
            head = handle.read(_MANIFEST_HEAD_BYTES)
    except OSError:
        return None
    return _name_in(head)


def scan_tree(root: str, found: dict[str, str], depth: int = 0) -> None:
    """Collect the packages below ``root`` into ``found`` (name -> folder; the first folder of
    a name is kept), as rospack crawls a package path entry.

    One ``scandir`` a folder, which tells its manifest, its ignore markers and its
    sub-folders apart by the entries' types: a package path holding ``/usr/share`` has some
    4,000 folders and 60,000 entries, and a stat and a sort of every entry per folder cost
    about a third of the crawl."""
    if depth > MAX_SCAN_DEPTH:
        return
    manifest = ignored = False
    subdirs: list[str] = []
    try:
        with os.scandir(root) as entries:
            for entry in entries:
                name = entry.name
                if name == "package.xml" and entry.is_file():
                    manifest = True
                elif name in IGNORE_MARKERS:
                    ignored = True
                elif not name.startswith(".") and entry.is_dir():
                    subdirs.append(name)
    except OSError:  # a folder that cannot be listed can still hold a readable manifest
        manifest, ignored = os.path.isfile(os.path.join(root, "package.xml")), True
    if manifest:
        name = manifest_name(os.path.join(root, "package.xml")) or os.path.basename(root)
        found.setdefault(name, root)
        return
    if ignored:
        return
    for name in sorted(subdirs):
        scan_tree(os.path.join(root, name), found, depth + 1)


def split_paths(value: str | None) -> list[str]:
    """The entries of a path variable (``ROS_PACKAGE_PATH``, ``AMENT_PREFIX_PATH``)."""
    return [p for p in value.split(os.pathsep) if p] if value else []


def ament_packages(prefix: str) -> list[str]:
    """Packages installed in an ament prefix, as ament_index_python finds them.

    ament_index_python (``get_packages_with_prefixes``, ``get_package_prefix``) knows a package
    by its marker file ``<prefix>/share/ament_index/resource_index/packages/<name>`` (hidden
    names skipped) and returns ``<prefix>/share/<name>`` as its share directory, whether or not
    a package.xml is installed there. A ``share/<name>/package.xml`` without a marker (a
    hand-made prefix) is accepted too, after the marked ones.
    """
    names: list[str] = []
    try:
        markers = sorted(os.scandir(os.path.join(prefix, _AMENT_MARKERS)), key=lambda e: e.name)
    except OSError:
        markers = []
    names += [e.name for e in markers if not e.name.startswith(".") and e.is_file()]
    try:
        entries = sorted(os.scandir(os.path.join(prefix, "share")), key=lambda e: e.name)
    except OSError:
        entries = []
    names += [
        e.name
        for e in entries
        if e.is_dir()
        and e.name not in names
        and os.path.isfile(os.path.join(e.path, "package.xml"))
    ]
    return names
