"""What every bag writer offers the recorder, and when a recording is split."""

from __future__ import annotations

from abc import ABC, abstractmethod
from dataclasses import dataclass

from robomodel.runtime.msg import Message
from robomodel.runtime.qos import QoSProfile

__all__ = ["NO_SPLIT", "BagWriter", "SplitPolicy"]


@dataclass(frozen=True, slots=True)
class SplitPolicy:
    """Start a new file past ``max_bytes`` or ``max_duration_ns`` (``ros2 bag record``'s
    ``--max-bag-size`` and ``--max-bag-duration``); None is no limit."""

    max_bytes: int | None = None
    max_duration_ns: int | None = None

    @property
    def splits(self) -> bool:
        return self.max_bytes is not None or self.max_duration_ns is not None

    def due(self, size_bytes: int, first_ns: int | None, now_ns: int) -> bool:
        """Whether the current file, ``size_bytes`` big and first written at ``first_ns``, is
        full when a message of time ``now_ns`` arrives."""
        if self.max_bytes is not None and size_bytes >= self.max_bytes:
            return True
        return (
            self.max_duration_ns is not None
            and first_ns is not None
            and now_ns - first_ns >= self.max_duration_ns
        )


NO_SPLIT = SplitPolicy()


class BagWriter(ABC):
    """A recording in progress. Messages arrive as CDR, with receive and publish time.

    ``flush`` makes everything written so far readable by another process (and survive a
    SIGKILL of this one); ``close`` finishes the files with their indexes.
    """

    message_count: int = 0

    @abstractmethod
    def add_topic(
        self, topic: str, msg_type: type[Message], offered_qos: tuple[QoSProfile, ...]
    ) -> None: ...

    @abstractmethod
    def write(
        self,
        topic: str,
        cdr: bytes,
        log_time_ns: int,
        publish_time_ns: int,
        sequence: int = 0,
    ) -> None: ...

    @abstractmethod
    def flush(self) -> None: ...

    @abstractmethod
    def close(self) -> None: ...

    @property
    @abstractmethod
    def size_bytes(self) -> int:
        """Bytes written so far, over all files."""

    @property
    @abstractmethod
    def files(self) -> tuple[str, ...]:
        """The files written so far."""
