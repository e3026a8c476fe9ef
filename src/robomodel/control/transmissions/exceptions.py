"""Errors of the transmissions."""

from __future__ import annotations

from robomodel.control.exceptions import ControlError

__all__ = ["TransmissionError"]


class TransmissionError(ControlError):
    """A transmission that cannot be built (zero reduction, wrong number of joints, ...)."""
