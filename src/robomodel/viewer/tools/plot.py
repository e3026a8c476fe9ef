"""Plot (rqt_plot): numeric fields of any topics against time, in a moving window.

Series are added by field path as in rqt_plot (``/joint_states/position[0]``,
``/joint1_position_controller/state/process_value``). The x axis is rqt_plot's: seconds since
the plot started (rqt_plot: its widget's start; here the Plot tool's, with the viewer; Clear
keeps it, as rqt_plot's Clear does) on ROS time, the viewer node's clock (simulated time under
``use_sim_time``, as ``rospy.get_time()``). A sample is placed at its message's header stamp
when it has one (rqt_plot's rosplot.py), else at its arrival. A stamp of zero, or one more than
:data:`STAMP_TOLERANCE_S` from the clock (a simulator's stamps while the viewer runs on wall
time), is not on that clock and would put the sample outside every window: such a sample is
placed at its arrival too.

The chart is viser's uPlot, redrawn at 10 Hz with every series on one time axis: the union of
the samples' times, each series interpolated linearly between its own samples, from the moment
every series has a sample (uPlot needs one x array for all series).
"""

from __future__ import annotations

import collections
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from robomodel.errors import RobomodelError
from robomodel.runtime.msg import Message
from robomodel.runtime.node import Subscription
from robomodel.viewer.markup import Markup, code, md, safe_markdown
from robomodel.viewer.tools.base import ToolContext
from robomodel.viewer.tools.field_path import FieldPath, field_value, resolve_field_path

__all__ = ["STAMP_TOLERANCE_S", "PlotData", "PlotTool", "Series", "sample_time_s"]

STAMP_TOLERANCE_S = 60.0  # a header stamp this far from the clock is on another clock

_COLOURS = ("#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b", "#e377c2")
_MAX_POINTS = 600  # per redraw: plenty for a panel a few hundred pixels wide
_MAX_SAMPLES = 20000  # per series (about 3 min at 100 Hz)


@dataclass
class Series:
    """One plotted field and its samples (times [s] from the plot's start, values)."""

    path: FieldPath
    times_s: collections.deque[float] = field(
        default_factory=lambda: collections.deque(maxlen=_MAX_SAMPLES)
    )
    values: collections.deque[float] = field(
        default_factory=lambda: collections.deque(maxlen=_MAX_SAMPLES)
    )


def sample_time_s(msg: Message, arrival_s: float) -> float:
    """When a sample of ``msg`` arriving at ``arrival_s`` (ROS time [s]) was taken: its header
    stamp if it has one on the same clock, else ``arrival_s`` (see the module docstring)."""
    header = getattr(msg, "header", None)
    stamp = getattr(header, "stamp", None)
    if stamp is None:
        return arrival_s
    sec = getattr(stamp, "sec", getattr(stamp, "secs", 0))
    nanosec = getattr(stamp, "nanosec", getattr(stamp, "nsecs", 0))
    stamp_s = int(sec) + int(nanosec) * 1e-9
    if stamp_s == 0.0 or abs(stamp_s - arrival_s) > STAMP_TOLERANCE_S:
        return arrival_s
    return stamp_s


class PlotData:
    """The series and the windowed arrays for the chart.

    Args:
        now_s: The plot's clock: ROS time [s] (the viewer node's).
    """

    def __init__(self, now_s: Callable[[], float]) -> None:
        self.series: list[Series] = []
        self.now_s = now_s
        self.start_s = now_s()  # x = 0

    def add(self, path: FieldPath) -> Series:
        series = Series(path)
        self.series.append(series)
        return series

    def record(self, series: Series, msg: Message, now_s: float | None = None) -> None:
        """Add ``msg``'s value to ``series``; ``now_s``: its arrival (default: the clock's now)."""
        value = field_value(msg, series.path.steps)
        if value is None:
            return
        arrival_s = self.now_s() if now_s is None else now_s
        t = sample_time_s(msg, arrival_s) - self.start_s
        if series.times_s and t < series.times_s[-1]:
            t = series.times_s[-1]  # a stamp older than the last sample's: keep time ordered
        series.times_s.append(t)
        series.values.append(value)

    def clear(self) -> None:
        """Remove every series; the plot's start stays (rqt_plot's Clear)."""
        self.series = []

    def window(
        self, window_s: float, now_s: float | None = None
    ) -> tuple[NDArray[np.float64], ...]:
        """``(x, y_1, ..., y_n)`` over the last ``window_s`` seconds (empty before data)."""
        now = (self.now_s() if now_s is None else now_s) - self.start_s
        empty = tuple(np.zeros(0) for _ in range(len(self.series) + 1))
        if not self.series or any(not s.times_s for s in self.series):
            return empty
        start = max([now - window_s, *(s.times_s[0] for s in self.series)])
        arrays = [(np.asarray(s.times_s), np.asarray(s.values)) for s in self.series]
        x = np.unique(np.concatenate([t[t >= start] for t, _ in arrays]))
        if x.size == 0:
            return empty
        if x.size > _MAX_POINTS:
            x = np.linspace(x[0], x[-1], _MAX_POINTS)
        return (x, *(np.interp(x, t, v) for t, v in arrays))


class PlotTool:
    """The "Plot" folder: a path box, Add, Clear, the window length, Pause, and the chart."""

    def __init__(self, tools: ToolContext) -> None:
        self.tools = tools
        gui = tools.server.gui
        clock = tools.node.get_clock()
        self.data = PlotData(clock.now_s)
        self._subscriptions: dict[str, Subscription[Any]] = {}
        self.path = gui.add_text("Field", "/joint_states/position[0]", hint="/topic/field[i]")
        add = gui.add_button("Add series")
        clear = gui.add_button("Clear")
        self.window_s = gui.add_number("Window [s]", 10.0, min=1.0, max=300.0, step=1.0)
        self.paused = gui.add_checkbox("Pause", False)
        self.status = safe_markdown(gui, md("*no series*"))
        self.chart: Any = None
        self._gui = gui
        self._folder = gui.add_folder("Chart")
        add.on_click(lambda _e: self.add(str(self.path.value)))
        clear.on_click(lambda _e: tools.post(self.clear))
        tools.post(lambda: tools.node.create_timer(0.1, self.redraw))

    def add(self, text: str) -> None:
        """Resolve ``text`` against the known topics and subscribe (from a GUI thread)."""
        try:
            path = resolve_field_path(text, self.tools.topic_types())
        except RobomodelError as exc:
            self.status.content = md("**refused:** {}", exc)
            return
        self.tools.post(lambda: self._add(path))

    def _add(self, path: FieldPath) -> None:
        self.data.add(path)
        self._subscribe(path)
        self._rebuild_chart()

    def _subscribe(self, path: FieldPath) -> None:
        if path.topic in self._subscriptions:
            return

        def on_msg(msg: Message) -> None:
            now = self.data.now_s()
            for series in self.data.series:
                if series.path.topic == path.topic:
                    self.data.record(series, msg, now)

        self._subscriptions[path.topic] = self.tools.node.create_subscription(
            path.msg_type, path.topic, on_msg, 100
        )

    def clear(self) -> None:
        for subscription in self._subscriptions.values():
            subscription.destroy()
        self._subscriptions = {}
        self.data.clear()
        self._rebuild_chart()

    def _rebuild_chart(self) -> None:
        """Drop the chart; :meth:`redraw` makes a new one once every series has data (a uPlot
        created without data never scales its x axis)."""
        if self.chart is not None:
            self.chart.remove()
            self.chart = None
        names = [s.path.text for s in self.data.series]
        self.status.content = (
            Markup("\n".join(md("- {}", code(n)) for n in names)) if names else md("*no series*")
        )

    def _make_chart(self, data: tuple[NDArray[np.float64], ...]) -> None:
        series: list[dict[str, Any]] = [{"label": "t [s]"}]
        series += [
            {"label": s.path.text, "stroke": _COLOURS[k % len(_COLOURS)], "width": 2}
            for k, s in enumerate(self.data.series)
        ]
        with self._folder:
            self.chart = self._gui.add_uplot(
                data=data,
                series=tuple(series),
                scales={"x": {"time": False}},
                legend={"show": True},
                aspect=1.4,
            )

    def redraw(self) -> None:
        if self.paused.value or not self.data.series:
            return
        data = self.data.window(float(self.window_s.value))
        if data[0].size == 0:
            return
        if self.chart is None:
            self._make_chart(data)
        else:
            self.chart.data = data
