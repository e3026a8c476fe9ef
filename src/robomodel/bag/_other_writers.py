"""rosbag2 folders with SQLite 3 storage and ROS 1 ``.bag`` files, written with rosbags.

- SQLite 3 (``--storage sqlite3``): rosbags' rosbag2 writer, which keeps one time per message
  (the receive time) and cannot split; a killed recording is not recovered.
- ROS 1 (``--ros1 FILE.bag``): rosbags' rosbag1 writer. Messages are converted to ROS 1
  serialization with robomodel's ROS 1 types (md5sums and definitions as genmsg makes them);
  the time kept is the receive time, as ``rosbag record`` keeps it. As ``rosbag record``
  does, the file is ``FILE.bag.active`` until the recording ends; a killed recording keeps the
  chunks written (every 1 MiB) and needs ``rosbag reindex``, as ROS 1's own does.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from robomodel.bag._deps import require
from robomodel.bag._writer_base import NO_SPLIT, BagWriter, SplitPolicy
from robomodel.bag.exceptions import BagWriteError
from robomodel.bag.typedefs import rihs01, ros2msg_definition
from robomodel.runtime.msg import Message, deserialize
from robomodel.runtime.qos import Durability, QoSProfile, Reliability

__all__ = ["Ros1BagWriter", "Sqlite3FolderWriter"]


def _rosbags_qos(qos: QoSProfile) -> Any:
    interfaces = require("rosbags.interfaces", "writing SQLite 3 bags")
    never = interfaces.QosTime(9223372036, 854775807)
    reliable = qos.reliability is Reliability.RELIABLE
    latched = qos.durability is Durability.TRANSIENT_LOCAL
    return interfaces.Qos(
        interfaces.QosHistory.KEEP_LAST,
        qos.depth,
        interfaces.QosReliability.RELIABLE if reliable else interfaces.QosReliability.BEST_EFFORT,
        interfaces.QosDurability.TRANSIENT_LOCAL if latched else interfaces.QosDurability.VOLATILE,
        never,
        never,
        interfaces.QosLiveliness.AUTOMATIC,
        never,
        False,
    )


class Sqlite3FolderWriter(BagWriter):
    """A rosbag2 folder with one ``.db3`` file."""

    def __init__(self, folder: Path, *, split: SplitPolicy = NO_SPLIT) -> None:
        rosbag2 = require("rosbags.rosbag2", "writing SQLite 3 bags")
        if split.splits:
            raise BagWriteError(str(folder), "splitting needs --storage mcap")
        if folder.exists():
            raise BagWriteError(str(folder), "exists already; give another output with -o")
        self.folder = folder
        self._writer = rosbag2.Writer(
            folder, version=9, storage_plugin=rosbag2.StoragePlugin.SQLITE3
        )
        self._writer.open()
        self._connections: dict[str, Any] = {}
        self.message_count = 0
        self._bytes = 0

    def add_topic(
        self, topic: str, msg_type: type[Message], offered_qos: tuple[QoSProfile, ...]
    ) -> None:
        if topic in self._connections:
            return
        self._connections[topic] = self._writer.add_connection(
            topic,
            msg_type.__typename__,
            msgdef=ros2msg_definition(msg_type),
            rihs01=rihs01(msg_type),
            offered_qos_profiles=[_rosbags_qos(q) for q in offered_qos],
        )

    def write(
        self, topic: str, cdr: bytes, log_time_ns: int, publish_time_ns: int, sequence: int = 0
    ) -> None:
        self._writer.write(self._connections[topic], log_time_ns, cdr)
        self.message_count += 1
        self._bytes += len(cdr)

    def flush(self) -> None:
        """rosbags commits SQLite transactions itself; nothing to force here."""

    def close(self) -> None:
        self._writer.close()

    @property
    def size_bytes(self) -> int:
        return self._bytes

    @property
    def files(self) -> tuple[str, ...]:
        return tuple(str(p) for p in sorted(self.folder.glob("*.db3")))


class Ros1BagWriter(BagWriter):
    """A ROS 1 bag (``path``), or ``stem_0.bag``, ``stem_1.bag``, ... when splitting."""

    def __init__(self, path: Path, *, split: SplitPolicy = NO_SPLIT) -> None:
        self._rosbag1 = require("rosbags.rosbag1", "writing ROS 1 bags")
        from robomodel.runtime.transport.ros1.ros1_types import ros1_type

        self._ros1_type = ros1_type
        self.path = path
        self._split = split
        self._topics: dict[str, tuple[type[Message], bool]] = {}
        self._done: list[Path] = []
        self._done_bytes = 0
        self.message_count = 0
        self._writer, self._target = self._open()
        self._connections: dict[str, Any] = {}
        self._first_ns: int | None = None

    def _open(self) -> tuple[Any, Path]:
        target = self.path
        if self._split.splits:
            target = self.path.with_name(f"{self.path.stem}_{len(self._done)}.bag")
        active = target.with_name(target.name + ".active")
        for candidate in (target, active):
            if candidate.exists():
                raise BagWriteError(str(candidate), "exists already; give another file")
        writer = self._rosbag1.Writer(active)
        writer.open()
        return writer, target

    def add_topic(
        self, topic: str, msg_type: type[Message], offered_qos: tuple[QoSProfile, ...]
    ) -> None:
        from robomodel.runtime.transport.ros1.ros1_types import Ros1TypeError

        try:
            self._ros1_type(msg_type)
        except Ros1TypeError as exc:
            raise BagWriteError(str(self.path), f"cannot record {topic}: {exc}") from None
        latched = any(q.durability is Durability.TRANSIENT_LOCAL for q in offered_qos)
        self._topics.setdefault(topic, (msg_type, latched))

    def _connection(self, topic: str) -> Any:
        connection = self._connections.get(topic)
        if connection is None:
            msg_type, latched = self._topics[topic]
            kind = self._ros1_type(msg_type)
            package, name = kind.name.split("/")
            connection = self._writer.add_connection(
                topic,
                f"{package}/msg/{name}",  # rosbags' normalized name; the file says pkg/Name
                msgdef=kind.definition,
                md5sum=kind.md5sum,
                callerid="/robomodel_bag_record",
                latching=1 if latched else None,
            )
            self._connections[topic] = connection
        return connection

    def write(
        self, topic: str, cdr: bytes, log_time_ns: int, publish_time_ns: int, sequence: int = 0
    ) -> None:
        size = self._writer.bio.tell() if self._writer.bio else 0
        if self.message_count and self._split.due(size, self._first_ns, log_time_ns):
            self._finish()
            self._writer, self._target = self._open()
            self._connections = {}
            self._first_ns = None
        msg_type, _ = self._topics[topic]
        data = self._ros1_type(msg_type).encode(deserialize(cdr, msg_type))
        self._writer.write(self._connection(topic), log_time_ns, data)
        self._first_ns = log_time_ns if self._first_ns is None else self._first_ns
        self.message_count += 1

    def _finish(self) -> None:
        self._writer.close()
        self._target.with_name(self._target.name + ".active").replace(self._target)
        self._done.append(self._target)
        self._done_bytes += self._target.stat().st_size

    def flush(self) -> None:
        if self._writer.bio is not None:
            self._writer.bio.flush()

    def close(self) -> None:
        self._finish()

    @property
    def size_bytes(self) -> int:
        current = self._writer.bio.tell() if self._writer.bio is not None else 0
        return self._done_bytes + current

    @property
    def files(self) -> tuple[str, ...]:
        return tuple(str(p) for p in self._done)
