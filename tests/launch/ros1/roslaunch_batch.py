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
Every query mode loads the whole launch file, so each evaluates the same ``command=`` params
(``$(find xacro)/xacro ...``, and ``rosversion`` from roslaunch's root.xml): a command param's
command line is run once per batch, and its output, standard error and exit code are given
back to the batch's later command lines as the command would give them again.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
from typing import Any

_run_process = subprocess.Popen


class _Finished:
    """A command param's run, as roslaunch's loader uses it (``communicate``, ``returncode``)."""

    def __init__(self, returncode: int, out: bytes, err: bytes) -> None:
        self.returncode, self._out, self._err = returncode, out, err

    def communicate(self, input: Any = None, timeout: Any = None) -> tuple[bytes, None]:
        err = memoryview(self._err)
        while err:  # where the command's own standard error went
            err = err[os.write(2, err) :]
        return self._out, None


_finished: dict[tuple[Any, ...], _Finished] = {}


def _command_param(command: Any, **options: Any) -> Any:
    """roslaunch's loader runs a command param as ``Popen(argv, stdout=PIPE)``; the same argv
    in the same folder and environment is run once."""
    if set(options) != {"stdout"} or options["stdout"] != subprocess.PIPE:
        return _run_process(command, **options)
    key = (tuple(command), os.getcwd(), tuple(sorted(os.environ.items())))
    if key not in _finished:
        process = _run_process(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
        out, err = process.communicate()
        _finished[key] = _Finished(process.returncode, out, err)
    return _finished[key]


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

    subprocess.Popen = _command_param  # type: ignore[misc]
    calls = json.load(sys.stdin)
    results = [_run(argv) for argv in calls]
    sys.stdout.write(json.dumps(results))


if __name__ == "__main__":
    main()
