"""Child processes of a launch: each in a process group of its own, ended as a group.

As roslaunch's ``nodeprocess.py`` (1.16): a child starts in a new session (``os.setsid``), so
everything it starts (``sh -c "a & b"``) shares its process group; stopping sends SIGINT to the
group, waits ``DEFAULT_TIMEOUT_SIGINT`` (15 s), then SIGTERM, waits ``DEFAULT_TIMEOUT_SIGTERM``
(2 s), then SIGKILL. A command whose output is wanted (``<param command=>``,
``$(command ...)``) runs the same way, under a time limit and an output cap, and its group is
killed when it overruns either or when the launch is interrupted while it runs.
"""

from __future__ import annotations

import contextlib
import os
import selectors
import signal
import subprocess
import time
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

from robomodel.errors import RobomodelError

__all__ = [
    "COMMAND_TIMEOUT_S",
    "MAX_COMMAND_OUTPUT_BYTES",
    "SIGINT_TIMEOUT_S",
    "SIGTERM_TIMEOUT_S",
    "CommandError",
    "CommandOutput",
    "end_group",
    "run_bounded",
]

SIGINT_TIMEOUT_S = 15.0  # roslaunch's DEFAULT_TIMEOUT_SIGINT
SIGTERM_TIMEOUT_S = 2.0  # roslaunch's DEFAULT_TIMEOUT_SIGTERM
COMMAND_TIMEOUT_S = 60.0
MAX_COMMAND_OUTPUT_BYTES = 64 * 1024 * 1024


class CommandError(RobomodelError):
    """A command that overran its time limit or output cap (its process group is killed)."""


@dataclass(frozen=True, slots=True)
class CommandOutput:
    """What a finished command gave: exit code, standard output and error (bytes)."""

    returncode: int
    stdout: bytes
    stderr: bytes


def _signal_group(proc: subprocess.Popen[bytes] | subprocess.Popen[str], sig: int) -> None:
    with contextlib.suppress(ProcessLookupError, PermissionError):
        os.killpg(proc.pid, sig)


def end_group(
    proc: subprocess.Popen[bytes] | subprocess.Popen[str],
    *,
    sigint_timeout_s: float = SIGINT_TIMEOUT_S,
    sigterm_timeout_s: float = SIGTERM_TIMEOUT_S,
) -> None:
    """End ``proc`` and its whole process group: SIGINT, then SIGTERM, then SIGKILL.

    ``proc`` must have been started with ``start_new_session=True`` (its pid is its group).
    The group is signalled even when the leader has already exited, so that a background
    child (``sh -c "sleep 999 &"``) does not outlive it.
    """
    for sig, wait_s in ((signal.SIGINT, sigint_timeout_s), (signal.SIGTERM, sigterm_timeout_s)):
        _signal_group(proc, sig)
        try:
            proc.wait(wait_s)
        except subprocess.TimeoutExpired:
            continue
        if not _group_alive(proc.pid):
            return
    _signal_group(proc, signal.SIGKILL)
    proc.wait()


def _group_alive(pgid: int) -> bool:
    try:
        os.killpg(pgid, 0)
    except (ProcessLookupError, PermissionError):
        return False
    return True


def run_bounded(
    argv: Sequence[str],
    *,
    timeout_s: float = COMMAND_TIMEOUT_S,
    max_output_bytes: int = MAX_COMMAND_OUTPUT_BYTES,
    cwd: str | None = None,
    env: Mapping[str, str] | None = None,
    merge_stderr: bool = False,
) -> CommandOutput:
    """Run ``argv`` (no shell) in a group of its own and collect its output, bounded.

    Raises:
        CommandError: it ran longer than ``timeout_s`` or wrote more than
            ``max_output_bytes`` (the group is killed at once).
        OSError: it could not be started (FileNotFoundError, PermissionError).
    """
    proc = subprocess.Popen(
        list(argv),
        stdin=subprocess.DEVNULL,
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT if merge_stderr else subprocess.PIPE,
        cwd=cwd,
        env=None if env is None else dict(env),
        start_new_session=True,
    )
    try:
        out, err = _collect(proc, timeout_s, max_output_bytes)
    except BaseException:  # overrun, Ctrl-C, SIGTERM turned into an exception: no orphans
        _signal_group(proc, signal.SIGKILL)
        proc.wait()
        raise
    finally:
        for stream in (proc.stdout, proc.stderr):
            if stream is not None:
                stream.close()
    _signal_group(proc, signal.SIGKILL)  # whatever it left running in the background
    return CommandOutput(proc.wait(), out, err)


def _timed_out(timeout_s: float) -> CommandError:
    return CommandError(
        f"did not finish within {timeout_s:g} s (change the limit with --command-timeout SECONDS)"
    )


def _collect(
    proc: subprocess.Popen[bytes], timeout_s: float, max_output_bytes: int
) -> tuple[bytes, bytes]:
    chunks: dict[object, list[bytes]] = {}
    total = 0
    deadline = time.monotonic() + timeout_s
    with selectors.DefaultSelector() as selector:
        for stream in (proc.stdout, proc.stderr):
            if stream is not None:
                selector.register(stream, selectors.EVENT_READ)
                chunks[stream] = []
        while selector.get_map():
            left = deadline - time.monotonic()
            if left <= 0:
                raise _timed_out(timeout_s)
            for key, _ in selector.select(min(left, 0.5)):
                data = os.read(key.fd, 65536)
                if not data:
                    selector.unregister(key.fileobj)
                    continue
                total += len(data)
                if total > max_output_bytes:
                    raise CommandError(
                        f"wrote more than {max_output_bytes / 2**20:.0f} MiB of output "
                        "(the limit for a command's output)"
                    )
                chunks[key.fileobj].append(data)
    try:
        proc.wait(max(deadline - time.monotonic(), 0.01))
    except subprocess.TimeoutExpired:  # closed its output but runs on
        raise _timed_out(timeout_s) from None
    out = b"".join(chunks.get(proc.stdout, []))
    err = b"".join(chunks.get(proc.stderr, []))
    return out, err
