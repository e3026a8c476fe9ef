"""rospy's exceptions, under robomodel's root error."""

from __future__ import annotations

from robomodel.errors import RobomodelError

__all__ = [
    "ROSException",
    "ROSInitException",
    "ROSInternalException",
    "ROSInterruptException",
    "ROSSerializationException",
    "ROSTimeMovedBackwardsException",
    "ServiceException",
    "TransportException",
    "TransportInitError",
    "TransportTerminated",
]


class ROSException(RobomodelError):
    """The root of rospy's errors."""


class ROSSerializationException(ROSException):
    """A message that cannot be serialized."""


class ROSInitException(ROSException):
    """rospy used before ``init_node``, or ``init_node`` that cannot finish."""


class ROSInterruptException(ROSException, KeyboardInterrupt):
    """A sleep or wait that ended because the node shut down (Ctrl-C, ``signal_shutdown``)."""


class ROSTimeMovedBackwardsException(ROSInterruptException):
    """ROS time (``/clock``) jumped back during a sleep."""

    def __init__(self, time: float) -> None:
        super().__init__(f"ROS time moved backwards by {time} s")
        self.time = time


class ROSInternalException(Exception):
    """An error inside rospy itself."""


class TransportException(ROSException):
    """A connection to a peer failed."""


class TransportTerminated(TransportException):
    """A connection that the peer closed."""


class TransportInitError(TransportException):
    """A connection that could not be opened."""


class ServiceException(ROSException):
    """A service call that failed: no provider, or the provider answered an error."""
