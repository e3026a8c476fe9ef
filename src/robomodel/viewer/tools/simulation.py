"""Simulation controls (Gazebo's play / pause / step / reset bar) for ``robomodel sim``.

The buttons call the simulator's services on the bus (``/gazebo/pause_physics``,
``/gazebo/unpause_physics`` and ``/gazebo/reset_world``, std_srvs/Empty; ``/gazebo/step``,
ros_gz_interfaces/ControlWorld with ``multi_step``), so they work for a simulator in this
process or in another one. The status line shows the sim time from /clock
and the real-time factor measured over the last second of /clock messages, as Gazebo's bottom
bar does. Without a simulator on the bus the folder says so and the buttons do nothing.
"""

from __future__ import annotations

import collections
import time
from typing import Any

from robomodel.errors import RobomodelError
from robomodel.runtime.msg import Clock, Message
from robomodel.runtime.msg.types import ros_gz_interfaces as rgz
from robomodel.runtime.msg.types import std_srvs
from robomodel.viewer.markup import md, safe_markdown
from robomodel.viewer.tools.base import ToolContext

__all__ = ["RealTimeFactor", "SimulationTool"]

PAUSE = "/gazebo/pause_physics"
UNPAUSE = "/gazebo/unpause_physics"
STEP = "/gazebo/step"
RESET = "/gazebo/reset_world"
_WINDOW_S = 1.0
_CALL_TIMEOUT_S = 10.0  # a simulator stepping on a loaded machine answers late, not never


class RealTimeFactor:
    """Sim time advanced per wall second over a sliding window of (wall, sim) samples."""

    def __init__(self, window_s: float = _WINDOW_S) -> None:
        self.window_s = window_s
        self.samples: collections.deque[tuple[float, float]] = collections.deque()

    def add(self, wall_s: float, sim_s: float) -> None:
        if self.samples and sim_s < self.samples[-1][1]:
            self.samples.clear()  # the world was reset
        self.samples.append((wall_s, sim_s))
        while len(self.samples) > 2 and wall_s - self.samples[0][0] > self.window_s:
            self.samples.popleft()

    def factor(self, now_wall_s: float) -> float | None:
        """The factor, 0 when /clock has been still for a window, None before two samples."""
        if len(self.samples) < 2:
            return None
        (w0, s0), (w1, s1) = self.samples[0], self.samples[-1]
        if now_wall_s - w1 > self.window_s:
            return 0.0
        return (s1 - s0) / (w1 - w0) if w1 > w0 else None


class SimulationTool:
    """The "Simulation" folder (built inside the caller's container)."""

    def __init__(self, tools: ToolContext) -> None:
        self.tools = tools
        gui = tools.server.gui
        self.sim_time_s: float | None = None
        self.rtf = RealTimeFactor()
        self.last_reply: Message | None = None
        self.last_error = ""
        self.status = safe_markdown(gui, md("No simulator on the bus (start `robomodel sim`)."))
        self.pause = gui.add_button("Pause", hint="pause the physics (/gazebo/pause_physics)")
        self.play = gui.add_button("Play", hint="run the physics (/gazebo/unpause_physics)")
        self.steps = gui.add_number("Steps", 1, min=1, max=100000, step=1)
        self.step = gui.add_button("Step", hint="while paused: advance this many physics steps")
        self.reset = gui.add_button("Reset world", hint="time and poses back to the start")
        self.pause.on_click(lambda _e: self.call(PAUSE, std_srvs.Empty))
        self.play.on_click(lambda _e: self.call(UNPAUSE, std_srvs.Empty))
        self.step.on_click(lambda _e: self.call(STEP, rgz.ControlWorld, self._step_request()))
        self.reset.on_click(lambda _e: self.call(RESET, std_srvs.Empty))
        tools.post(self._subscribe)

    def _subscribe(self) -> None:
        self.tools.node.create_subscription(Clock, "/clock", self._on_clock, 10)
        self.tools.node.create_timer(0.5, self._show)

    def _on_clock(self, msg: Clock) -> None:
        self.sim_time_s = msg.clock.sec + msg.clock.nanosec * 1e-9
        self.rtf.add(time.monotonic(), self.sim_time_s)

    @property
    def available(self) -> bool:
        return PAUSE in self.tools.services

    def _show(self) -> None:
        if not self.available and self.sim_time_s is None:
            return
        if self.sim_time_s is None:
            self.status.content = md("Simulator found; waiting for /clock.")
            return
        factor = self.rtf.factor(time.monotonic())
        rtf = "paused" if factor == 0.0 else ("-" if factor is None else f"{factor:.2f}x")
        self.status.content = md(
            "Sim time **{} s** · real-time factor **{}**", f"{self.sim_time_s:.3f}", rtf
        )

    def _step_request(self) -> rgz.ControlWorld_Request:
        control = rgz.WorldControl(pause=True, multi_step=int(self.steps.value))
        return rgz.ControlWorld_Request(control)

    def call(self, service: str, srv_type: Any, request: Message | None = None) -> None:
        """Call ``service`` on the bus worker; the reply (or the error) is kept and shown."""

        def job() -> None:
            context = self.tools.node.context
            try:
                self.last_reply = self.tools.bus.query(
                    lambda: context.call_service(service, srv_type, request, _CALL_TIMEOUT_S)
                )
                self.last_error = ""
            except RobomodelError as exc:
                self.last_reply, self.last_error = None, str(exc)
                self.status.content = md("{}: {}", service, exc)

        self.tools.bus.submit(job)
