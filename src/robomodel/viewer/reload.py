"""Live reload: polling the modification times of a description and the files it includes.

Polling (a few times a second) needs no extra dependency and works the same on every
platform and filesystem, including editors that save by renaming a new file into place.
"""

from __future__ import annotations

import os
from collections.abc import Iterable

__all__ = ["FileWatcher"]

_Stamp = tuple[int, int] | None


def _stamp(path: str) -> _Stamp:
    try:
        st = os.stat(path)
    except OSError:
        return None
    return (st.st_mtime_ns, st.st_size)


class FileWatcher:
    """Remembers (mtime, size) of a set of files and reports when any of them changed."""

    def __init__(self, paths: Iterable[str] = ()) -> None:
        self._stamps: dict[str, _Stamp] = {}
        self.watch(paths)

    @property
    def paths(self) -> tuple[str, ...]:
        return tuple(self._stamps)

    def watch(self, paths: Iterable[str]) -> None:
        """Watch exactly ``paths`` from now on, taking their current state as the baseline."""
        self._stamps = {os.path.abspath(p): _stamp(os.path.abspath(p)) for p in paths}

    def add(self, paths: Iterable[str]) -> None:
        """Also watch ``paths`` (baseline: their current state), keeping the others."""
        for path in paths:
            full = os.path.abspath(path)
            self._stamps.setdefault(full, _stamp(full))

    def changed(self) -> tuple[str, ...]:
        """Files that changed (or appeared or vanished) since the last call; updates baselines."""
        changed = []
        for path, old in self._stamps.items():
            new = _stamp(path)
            if new != old:
                self._stamps[path] = new
                changed.append(path)
        return tuple(changed)
