"""Topic publisher (rqt_publisher): one field of a message set from an expression per tick.

The expression is rqt_publisher's (``sin(i/rate*speed)*diff + offset``), evaluated by
:class:`~robomodel.viewer.tools.expression.Expression` with ``i`` the message counter, ``rate``
the publishing rate [Hz], ``t = i / rate`` [s] and the user's variables. The other fields of
the message keep their defaults.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from robomodel.errors import RobomodelError
from robomodel.runtime.executor import Timer
from robomodel.runtime.msg import Message, get_message_type
from robomodel.runtime.node import Publisher
from robomodel.viewer.markup import code, md, safe_markdown
from robomodel.viewer.tools.base import ToolContext
from robomodel.viewer.tools.expression import Expression, parse_variables
from robomodel.viewer.tools.field_path import parse_steps, set_field

__all__ = ["ExpressionPublisher", "PublisherTool"]


@dataclass
class ExpressionPublisher:
    """The publishing state: type, field, expression, variables and the counter ``i``.

    Raises :class:`RobomodelError` (type, field, expression or variables) when built.
    """

    type_name: str
    field: str
    expression: str
    rate_hz: float
    variables: str = ""

    def __post_init__(self) -> None:
        if not (math.isfinite(self.rate_hz) and self.rate_hz > 0):
            raise RobomodelError(f"rate must be a positive number of Hz, got {self.rate_hz}")
        self.msg_type = get_message_type(self.type_name)
        self.steps = parse_steps(self.field)
        self.values = parse_variables(self.variables)
        names = ("i", "rate", "t", *self.values)
        self.compiled = Expression(self.expression, names)
        self.counter = 0
        self.message(0)  # fails now, not at the first tick, for a wrong field or expression

    def message(self, i: int) -> Message:
        value = self.compiled.evaluate(
            {**self.values, "i": float(i), "rate": self.rate_hz, "t": i / self.rate_hz}
        )
        return set_field(self.msg_type, self.steps, value)

    def next_message(self) -> Message:
        msg = self.message(self.counter)
        self.counter += 1
        return msg


class PublisherTool:
    """The "Topic Publisher" folder."""

    def __init__(self, tools: ToolContext) -> None:
        self.tools = tools
        gui = tools.server.gui
        self.state: ExpressionPublisher | None = None
        self.published = 0
        self._publisher: Publisher[Any] | None = None
        self._timer: Timer | None = None
        self._running = False
        self.topic = gui.add_text("Pub topic", "/joint1_position_controller/command")
        self.type = gui.add_text("Pub type", "std_msgs/msg/Float64")
        self.field = gui.add_text("Pub field", "data", hint="e.g. data, linear/x, data[0]")
        self.expression = gui.add_text(
            "Expression", "sin(i/rate*speed)*diff + offset", hint="i, rate [Hz], t [s], math"
        )
        self.variables = gui.add_text("Variables", "speed=1, diff=3.1415, offset=0")
        self.rate = gui.add_number("Rate [Hz]", 50.0, min=0.1, max=1000.0, step=0.1)
        self.enabled = gui.add_checkbox("Publishing", False)
        self.status = safe_markdown(gui, md("*stopped*"))
        self.enabled.on_update(lambda _e: self._toggle())

    def _toggle(self) -> None:
        if not self.enabled.value:
            self.tools.post(self._stop)
            if self._running:  # keep a refusal's reason on screen
                self.status.content = md("*stopped*")
            self._running = False
            return
        try:
            state = ExpressionPublisher(
                str(self.type.value),
                str(self.field.value),
                str(self.expression.value),
                float(self.rate.value),
                str(self.variables.value),
            )
        except RobomodelError as exc:
            self.status.content = md("**refused:** {}", exc)
            self.enabled.value = False
            return
        topic = str(self.topic.value).strip()
        self._running = True
        self.status.content = md("publishing {} on {}", state.msg_type.__typename__, code(topic))
        self.tools.post(lambda: self._start(topic, state))

    def _start(self, topic: str, state: ExpressionPublisher) -> None:
        self._stop()
        try:
            self._publisher = self.tools.node.create_publisher(state.msg_type, topic, 10)
        except RobomodelError as exc:
            self.status.content = md("**refused:** {}", exc)
            return
        self.state = state
        self._timer = self.tools.node.create_timer(1.0 / state.rate_hz, self.tick)

    def _stop(self) -> None:
        if self._timer is not None:
            self._timer.cancel()
            self._timer = None
        if self._publisher is not None:
            self._publisher.destroy()
            self._publisher = None
        self.state = None

    def tick(self) -> None:
        if self.state is None or self._publisher is None:
            return
        try:
            msg = self.state.next_message()
        except RobomodelError as exc:  # e.g. log(0) at some i: stop, say why
            self._stop()
            self._running = False
            self.status.content = md("**stopped:** {}", exc)
            self.enabled.value = False
            return
        self._publisher.publish(msg)
        self.published += 1
