"""Transmissions between actuator and joint spaces (ros_control / transmission_interface)."""

from robomodel.control.transmissions.adapter import BoundTransmission, TransmissionSet
from robomodel.control.transmissions.base import Transmission
from robomodel.control.transmissions.differential import DifferentialTransmission
from robomodel.control.transmissions.exceptions import TransmissionError
from robomodel.control.transmissions.loader import transmission_from_description
from robomodel.control.transmissions.simple import SimpleTransmission

__all__ = [
    "BoundTransmission",
    "DifferentialTransmission",
    "SimpleTransmission",
    "Transmission",
    "TransmissionError",
    "TransmissionSet",
    "transmission_from_description",
]
