"""genpy's ``Message`` base and its exceptions.

Every robomodel message class (robomodel's own, and the genpy- and rosidl-shaped faces of the
same types) has ROS 1's serialization, so ``isinstance(msg, genpy.Message)`` holds for all of
them, as it holds for every generated class under ROS 1. A class that derives from
:class:`Message` gets genpy's ``serialize``/``deserialize`` and ``_type``/``_md5sum``/
``_full_text`` from the ROS 1 type of its ``__typename__``.
"""

from __future__ import annotations

import io
from typing import Any

from robomodel.clientlibs.messages._genpy import (
    DeserializationError,
    MessageException,
    SerializationError,
)

__all__ = [
    "DeserializationError",
    "GenpyException",
    "Message",
    "MessageException",
    "SerializationError",
]

# The errors are the ones the genpy-flavoured message classes raise (one class each, so that
# ``except genpy.SerializationError`` catches what ``msg.serialize()`` raises).
GenpyException = MessageException


def _ros1_type(cls: type) -> Any:
    from robomodel.runtime.transport.ros1.ros1_types import Ros1TypeError, ros1_type

    try:
        return ros1_type(cls)
    except Ros1TypeError as exc:
        raise SerializationError(str(exc)) from None


class _MessageMeta(type):
    """Makes every robomodel message an instance of :class:`Message`."""

    def __instancecheck__(cls, instance: object) -> bool:
        return cls.__subclasscheck__(type(instance))

    def __subclasscheck__(cls, subclass: type) -> bool:
        from robomodel.runtime.msg import Message as RobomodelMessage

        if cls is Message and isinstance(subclass, type) and issubclass(subclass, RobomodelMessage):
            return True
        return type.__subclasscheck__(cls, subclass)


class _ClassProperty:
    """A read-only attribute of the class, computed on first access from the ROS 1 type."""

    def __init__(self, attribute: str) -> None:
        self.attribute = attribute

    def __get__(self, instance: object, owner: type) -> Any:
        return getattr(_ros1_type(owner), self.attribute)


class Message(metaclass=_MessageMeta):
    """genpy's message base: ``_type``, ``_md5sum``, ``_full_text``, ``serialize`` and
    ``deserialize``, for a robomodel message class that derives from it."""

    __slots__ = ()
    _type = _ClassProperty("name")
    _md5sum = _ClassProperty("md5sum")
    _full_text = _ClassProperty("definition")

    def serialize(self, buff: io.BytesIO) -> None:
        """Write the message in ROS 1's serialization to ``buff``."""
        from robomodel.runtime.transport.ros1.ros1_types import Ros1CodecError

        try:
            buff.write(_ros1_type(type(self)).encode(self))
        except Ros1CodecError as exc:
            raise SerializationError(f"{type(self).__name__}: {exc}") from None

    def deserialize(self, data: bytes) -> Message:
        """Fill the message from ROS 1's serialization ``data``; returns the message."""
        from robomodel.runtime.transport.ros1.ros1_types import Ros1CodecError

        try:
            decoded = _ros1_type(type(self)).decode(data)
        except Ros1CodecError as exc:
            raise DeserializationError(f"{type(self).__name__}: {exc}") from None
        for name, _ in type(self).__fields__:  # type: ignore[attr-defined]
            setattr(self, name, getattr(decoded, name))
        return self
