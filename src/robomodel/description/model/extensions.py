"""Non-kinematic URDF extensions: transmissions, ``<gazebo>`` and ``<ros2_control>`` blocks."""

from __future__ import annotations

import enum
from dataclasses import dataclass, field

from robomodel.description.model.raw import RawElement
from robomodel.description.model.source import SourceSpan

__all__ = [
    "ComponentInterfaces",
    "GazeboBlock",
    "Interface",
    "Ros2Control",
    "Transmission",
    "TransmissionActuator",
    "TransmissionJoint",
    "TransmissionStyle",
]

Params = tuple[tuple[str, str], ...]


class TransmissionStyle(enum.Enum):
    """How the transmission was written, so the writer can reproduce it."""

    ROS1 = "ros1"  # <type>...</type> child, camelCase mechanicalReduction, hardwareInterface
    ROS1_TYPE_ATTRIBUTE = "ros1_type_attribute"  # PR2: <transmission type="...">
    ROS2 = "ros2"  # <plugin>...</plugin>, mechanical_reduction, role attributes


@dataclass(frozen=True, slots=True)
class TransmissionJoint:
    """A joint side of a transmission."""

    name: str
    role: str | None = None
    hardware_interfaces: tuple[str, ...] = ()
    mechanical_reduction: float | None = None
    offset: float | None = None
    extra: tuple[RawElement, ...] = ()  # other children (e.g. drake:rotor_inertia), verbatim


@dataclass(frozen=True, slots=True)
class TransmissionActuator:
    """An actuator side of a transmission."""

    name: str
    role: str | None = None
    hardware_interfaces: tuple[str, ...] = ()
    mechanical_reduction: float | None = None
    offset: float | None = None
    extra: tuple[RawElement, ...] = ()  # other children (e.g. drake:rotor_inertia), verbatim


@dataclass(frozen=True, slots=True)
class Transmission:
    """A ``<transmission>`` in the ROS 1 (``<type>``) or ROS 2 (``<plugin>``) form.

    ``mechanical_reduction`` is the transmission-level reduction of the old PR2 form.
    """

    name: str
    type: str
    style: TransmissionStyle = TransmissionStyle.ROS1
    joints: tuple[TransmissionJoint, ...] = ()
    actuators: tuple[TransmissionActuator, ...] = ()
    mechanical_reduction: float | None = None
    extra: tuple[RawElement, ...] = ()
    span: SourceSpan | None = field(default=None, compare=False, repr=False)


@dataclass(frozen=True, slots=True)
class GazeboBlock:
    """A ``<gazebo>`` extension block: its ``reference`` (link/joint or None) and raw XML."""

    reference: str | None
    xml: str
    span: SourceSpan | None = field(default=None, compare=False, repr=False)


@dataclass(frozen=True, slots=True)
class Interface:
    """A command or state interface of a ros2_control component (``position``, ...)."""

    name: str
    params: Params = ()
    data_type: str | None = None
    size: int | None = None

    def param(self, key: str) -> str | None:
        for name, value in self.params:
            if name == key:
                return value
        return None

    @property
    def initial_value(self) -> str | None:
        return self.param("initial_value")

    @property
    def min(self) -> str | None:
        return self.param("min")

    @property
    def max(self) -> str | None:
        return self.param("max")


@dataclass(frozen=True, slots=True)
class ComponentInterfaces:
    """A ``<joint>``, ``<sensor>`` or ``<gpio>`` of a ``<ros2_control>`` block."""

    name: str
    command_interfaces: tuple[Interface, ...] = ()
    state_interfaces: tuple[Interface, ...] = ()
    params: Params = ()
    attributes: Params = ()


@dataclass(frozen=True, slots=True)
class Ros2Control:
    """A ``<ros2_control>`` block: one hardware component and its interfaces."""

    name: str
    type: str  # "system", "actuator" or "sensor"
    hardware_plugin: str | None = None
    hardware_params: Params = ()
    joints: tuple[ComponentInterfaces, ...] = ()
    sensors: tuple[ComponentInterfaces, ...] = ()
    gpios: tuple[ComponentInterfaces, ...] = ()
    transmissions: tuple[Transmission, ...] = ()
    attributes: Params = ()  # other attributes of <ros2_control> (is_async, rw_rate, ...)
    extra: tuple[RawElement, ...] = ()
    span: SourceSpan | None = field(default=None, compare=False, repr=False)
