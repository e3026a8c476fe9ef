"""The bag layer's errors: every one names the file, and the byte offset where it knows it."""

from __future__ import annotations

from robomodel.errors import RobomodelError

__all__ = ["BagError", "BagFormatError", "BagWriteError"]


class BagError(RobomodelError):
    """A bag that cannot be read or written as asked.

    Attributes:
        path: The file or folder concerned.
        offset: Byte offset in ``path`` where the problem starts, when known.
    """

    def __init__(self, path: str, reason: str, *, offset: int | None = None) -> None:
        self.path = path
        self.offset = offset
        self.reason = reason
        where = f"{path}: " if offset is None else f"{path}: at byte {offset}: "
        super().__init__(where + reason)


class BagFormatError(BagError):
    """Damaged or foreign input: not a bag, a truncated file, a chunk failing its CRC."""


class BagWriteError(BagError):
    """An output that cannot be created (it exists, a type has no ROS 1 form, ...)."""
