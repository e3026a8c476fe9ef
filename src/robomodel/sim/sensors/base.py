"""The base of simulated sensors: a site on the link, a rate, a topic, a message per update."""

from __future__ import annotations

from abc import ABC, abstractmethod
from typing import Any

import numpy as np

from robomodel.runtime.msg.schema import Message
from robomodel.runtime.msg.types.builtin_interfaces import Time
from robomodel.runtime.msg.types.std_msgs import Header
from robomodel.sim.sensors.spec import SensorSpec

__all__ = ["SimSensor"]


class SimSensor(ABC):
    """A sensor of one robot, measured from the MuJoCo state.

    Args:
        spec: What the URDF declared.
        model: The compiled model (the sensor's site is ``prefix + spec.name``).
        data: The state.
        prefix: The robot's frame prefix (also prefixes ``frame_id``).
        seed: Seed of the noise generator (runs are reproducible).
        site: The MuJoCo site (and camera) name, if not ``prefix + spec.name`` (world sensors).
    """

    message_type: type[Message]

    def __init__(
        self,
        spec: SensorSpec,
        model: Any,
        data: Any,
        *,
        prefix: str = "",
        seed: int = 0,
        site: str = "",
    ) -> None:
        self.spec = spec
        self.model = model
        self.data = data
        self.prefix = prefix
        self.frame_id = prefix + spec.frame
        self.site_name = site or prefix + spec.name
        self.site = int(model.site(self.site_name).id)
        self.body = int(model.site_bodyid[self.site])
        self.rng = np.random.default_rng(seed)

    def header(self, time_s: float) -> Header:
        return Header(stamp=Time.from_seconds(time_s), frame_id=self.frame_id)

    @abstractmethod
    def measure(self, time_s: float) -> Message:
        """The message for the current state."""
