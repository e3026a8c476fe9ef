"""tf2's exception family, with tf2's message texts (``tf2/include/tf2/exceptions.h``).

``LookupError`` also derives from Python's built-in ``LookupError`` so that generic handlers
still catch it.
"""

from __future__ import annotations

import builtins

from robomodel.errors import RobomodelError

__all__ = [
    "BackwardExtrapolationError",
    "ConnectivityError",
    "ExtrapolationError",
    "ForwardExtrapolationError",
    "InvalidArgumentError",
    "LookupError",
    "NoDataForExtrapolationError",
    "TransformError",
]


class TransformError(RobomodelError):
    """Root of the tf errors (tf2's ``TransformException``)."""


class LookupError(TransformError, builtins.LookupError):
    """A frame does not exist (tf2's ``LookupException``)."""


class ConnectivityError(TransformError):
    """The two frames are in different trees (tf2's ``ConnectivityException``)."""


class ExtrapolationError(TransformError):
    """The requested time is outside the buffered data (tf2's ``ExtrapolationException``)."""


class BackwardExtrapolationError(ExtrapolationError):
    """Requested time before the earliest data."""


class ForwardExtrapolationError(ExtrapolationError):
    """Requested time after the latest data."""


class NoDataForExtrapolationError(ExtrapolationError):
    """Only one sample, at another time."""


class InvalidArgumentError(TransformError, ValueError):
    """An empty frame id or one starting with ``/`` (tf2's ``InvalidArgumentException``)."""
