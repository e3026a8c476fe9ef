"""When the steps of a ROS 2 launch start: at once, after a ``TimerAction`` delay, or when
another step's process exits or starts (``RegisterEventHandler(OnProcessExit/OnProcessStart)``),
as launch's event loop does; and what an ``ExecuteProcess`` runs.

A step is duck-typed (``kind``, ``node``, ``command``, ``message``, ``delay_s``,
``after_exit_of``, ``after_start_of``), as :class:`robomodel.launch.ros2.LaunchStep` has them.
``ExecuteProcess(cmd=['ros2', 'run', PKG, EXE, ...])`` becomes that node, so its mapping runs;
any other command runs as a subprocess, its output prefixed with its name.
"""

from __future__ import annotations

import subprocess
import threading
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

from robomodel.launch.model import NodeSpec
from robomodel.launch.processes import end_group

__all__ = ["ProcessNode", "StepScheduler", "node_of_command"]


def node_of_command(command: Sequence[str], location: Any = None) -> NodeSpec | None:
    """``ros2 run PKG EXE [args] [--ros-args ...]`` as the node it starts (else None)."""
    words = list(command)
    if len(words) >= 4 and words[0].rsplit("/", 1)[-1] == "ros2" and words[1] == "run":
        args = words[4:]
        ros_args: list[str] = []
        if "--ros-args" in args:
            cut = args.index("--ros-args")
            args, ros_args = args[:cut], args[cut + 1 :]
        name = None
        remaps: list[tuple[str, str]] = []
        for i, word in enumerate(ros_args):
            if word in ("-r", "--remap") and i + 1 < len(ros_args):
                left, _, right = ros_args[i + 1].partition(":=")
                if left == "__node":
                    name = right
                else:
                    remaps.append((left, right))
        return NodeSpec(
            "ros2", words[2], words[3], name, args=tuple(args), remaps=tuple(remaps),
            location=location,
        )  # fmt: skip
    return None


class ProcessNode:
    """An ``ExecuteProcess`` command run as a subprocess, its output lines prefixed."""

    def __init__(self, command: Sequence[str], log: Callable[[str], None]) -> None:
        self.proc = subprocess.Popen(
            list(command),
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            stdin=subprocess.DEVNULL,
            text=True,
            start_new_session=True,  # its own process group, ended as a group (roslaunch)
        )
        self._thread = threading.Thread(target=self._pump, args=(log,), daemon=True)
        self._thread.start()

    def _pump(self, log: Callable[[str], None]) -> None:
        assert self.proc.stdout is not None
        for line in self.proc.stdout:
            log(line.rstrip("\n"))

    def stop(self) -> None:
        """SIGINT, SIGTERM, then SIGKILL to its whole group, with roslaunch's timeouts."""
        end_group(self.proc)

    def exit_code(self) -> int | None:
        return self.proc.poll()


@dataclass
class StepScheduler:
    """Starts each step when it is due; ``start(index, step)`` returns its running handle."""

    steps: Sequence[Any]
    start: Callable[[int, Any], Any]
    t0: float = field(default_factory=time.monotonic)
    handles: dict[int, Any] = field(default_factory=dict)
    pending: list[int] = field(default_factory=list)
    started_at: dict[int, float] = field(default_factory=dict)
    ended_at: dict[int, float] = field(default_factory=dict)

    def begin(self) -> None:
        self.t0 = time.monotonic()
        self.pending = list(range(len(self.steps)))
        self.poll()

    def _due(self, index: int) -> bool:
        step = self.steps[index]
        anchor = self.t0
        target = getattr(step, "after_exit_of", None)
        if target is not None:
            handle = self.handles.get(target)
            if handle is None or handle.exit_code() is None:
                return False
            anchor = self.ended_at.setdefault(target, time.monotonic())
        started = getattr(step, "after_start_of", None)
        if started is not None:
            if started not in self.handles:
                return False
            anchor = self.started_at.get(started, anchor)
        return time.monotonic() >= anchor + float(getattr(step, "delay_s", 0.0) or 0.0)

    def poll(self) -> None:
        """Start every pending step that is due (in file order)."""
        progressed = True
        while progressed:
            progressed = False
            for index in list(self.pending):
                if self._due(index):
                    self.pending.remove(index)
                    self.handles[index] = self.start(index, self.steps[index])
                    self.started_at[index] = time.monotonic()
                    progressed = True
