"""genpy on robomodel: ROS 1's ``Time`` and ``Duration`` values and the ``Message`` base of
generated ROS 1 message classes, with genpy's exceptions.

``genpy.Time``/``genpy.Duration`` keep genpy's semantics (``secs``/``nsecs`` kept canonical,
``to_sec``, ``to_nsec``, arithmetic and comparisons). ``isinstance(msg, genpy.Message)`` is true
for every robomodel message, whichever face (genpy's, rosidl's, robomodel's) its class is: each
one has ROS 1's serialization.
"""

from robomodel.clientlibs.genpy._message import (
    DeserializationError,
    GenpyException,
    Message,
    MessageException,
    SerializationError,
)
from robomodel.clientlibs.genpy._rostime import Duration, Time, TVal

__all__ = [
    "DeserializationError",
    "Duration",
    "GenpyException",
    "Message",
    "MessageException",
    "SerializationError",
    "TVal",
    "Time",
]
