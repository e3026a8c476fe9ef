"""rqt in the viewer: robot steering, plot, topic publisher and parameters.

One module per tool; each builds its controls in a collapsed folder of the page and does its
bus work on the viewer's loop thread (publishers, subscriptions, timers) or on the bus worker
(graph and parameter queries).
"""

from robomodel.viewer.tools.base import BusWorker, ToolContext
from robomodel.viewer.tools.expression import Expression, ExpressionError, parse_variables
from robomodel.viewer.tools.field_path import (
    FieldPath,
    FieldPathError,
    field_value,
    resolve_field_path,
    set_field,
)
from robomodel.viewer.tools.panel import ToolsPanel
from robomodel.viewer.tools.plot import PlotData
from robomodel.viewer.tools.publisher import ExpressionPublisher
from robomodel.viewer.tools.steering import SteeringCommand

__all__ = [
    "BusWorker",
    "Expression",
    "ExpressionError",
    "ExpressionPublisher",
    "FieldPath",
    "FieldPathError",
    "PlotData",
    "SteeringCommand",
    "ToolContext",
    "ToolsPanel",
    "field_value",
    "parse_variables",
    "resolve_field_path",
    "set_field",
]
