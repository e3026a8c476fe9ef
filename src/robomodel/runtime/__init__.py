"""The runtime layer: messages, topics, parameters and nodes, in-process or over Zenoh."""

from robomodel.runtime.clock import Clock, ManualClock, SimClock, SystemClock
from robomodel.runtime.context import BUSES, Context
from robomodel.runtime.node import Node, Publisher, Subscription
from robomodel.runtime.params import ParameterError, SetResult
from robomodel.runtime.qos import Durability, QoSProfile, Reliability, latched, sensor_data

__all__ = [
    "BUSES",
    "Clock",
    "Context",
    "Durability",
    "ManualClock",
    "Node",
    "ParameterError",
    "Publisher",
    "QoSProfile",
    "Reliability",
    "SetResult",
    "SimClock",
    "Subscription",
    "SystemClock",
    "latched",
    "sensor_data",
]
