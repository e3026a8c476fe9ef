"""tf2's exceptions as ``tf2_ros`` names them (``tf2_ros.LookupException``, ...).

They are robomodel's TF errors under tf2's names, so ``except tf2_ros.TransformException``
catches what robomodel's buffer raises, with tf2's message texts.
"""

from __future__ import annotations

from robomodel.tf.exceptions import (
    ConnectivityError,
    ExtrapolationError,
    InvalidArgumentError,
    LookupError,
    TransformError,
)

__all__ = [
    "ConnectivityException",
    "ExtrapolationException",
    "InvalidArgumentException",
    "LookupException",
    "TimeoutException",
    "TransformException",
    "TypeException",
]

TransformException = TransformError
LookupException = LookupError
ConnectivityException = ConnectivityError
ExtrapolationException = ExtrapolationError
InvalidArgumentException = InvalidArgumentError


class TimeoutException(TransformError):
    """tf2's ``TimeoutException``."""


class TypeException(TransformError):
    """tf2's ``TypeException``: ``Buffer.transform`` of a type it has no conversion for."""
