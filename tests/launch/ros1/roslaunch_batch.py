"""Debian's roslaunch run once per command line of a list, in one process of Debian's Python.

Run as ``/usr/bin/python3 roslaunch_batch.py`` (what ``/usr/bin/roslaunch`` runs: ``import
roslaunch; roslaunch.main()``) with a JSON list of argument lists on stdin. Each is given to
``roslaunch.main`` as its command line (and as ``sys.argv``, where roslaunch reads
``NAME:=VALUE``), its file descriptors 1 and 2 (what the command prints,
and what the commands it runs print) caught in files of their own; its exit code is that of
``sys.exit``, else 0. The answer on stdout is a JSON list of ``[code, stdout, stderr]``.

The query modes (``--dump-params``, ``--nodes``, ``--args``, ``--files``, ``--ros-args``) start
no ROS process, so one interpreter serves a test's several queries of one launch file: each
command line a process of its own paid for Python's start and roslaunch's imports again.
"""

from __future__ import annotations

import json
import os
import sys
import tempfile


def _run(argv: list[str]) -> list[object]:
    import roslaunch

    with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as err:
        saved = os.dup(1), os.dup(2)
        sys.stdout.flush()
        sys.stderr.flush()
        os.dup2(out.fileno(), 1)
        os.dup2(err.fileno(), 2)
        sys.argv = ["roslaunch", *argv]  # roslaunch's loader reads NAME:=VALUE from sys.argv
        try:
            roslaunch.main(sys.argv)
            code = 0
        except SystemExit as stop:
            code = stop.code if isinstance(stop.code, int) else (0 if stop.code is None else 1)
        finally:
            sys.stdout.flush()
            sys.stderr.flush()
            os.dup2(saved[0], 1)
            os.dup2(saved[1], 2)
            os.close(saved[0])
            os.close(saved[1])
        texts = []
        for caught in (out, err):
            caught.seek(0)
            texts.append(caught.read().decode("utf-8", "replace"))
    return [code, *texts]


def main() -> None:
    import roslaunch  # noqa: F401  (its import-time output goes to the batch's own stderr)

    calls = json.load(sys.stdin)
    results = [_run(argv) for argv in calls]
    sys.stdout.write(json.dumps(results))


if __name__ == "__main__":
    main()
