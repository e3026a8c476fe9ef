"""rosbag2's ``metadata.yaml`` (version 9, Jazzy's): written beside the storage files, read
back for the file list, the storage and the offered QoS of each topic.

The layout follows rosbag2_storage's ``yaml.hpp`` (``rosbag2_bagfile_information``). A file read
back is bounded: at most ``MAX_METADATA_BYTES``, no YAML aliases, nesting at most
``MAX_DATA_DEPTH`` levels, and at most ``MAX_BAG_FILES`` storage files.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import yaml

from robomodel._atomic import atomic_write_text
from robomodel._files import UserFileError, read_user_text
from robomodel._yaml_bounded import YamlNestingError, load_yaml_data
from robomodel.bag.exceptions import BagFormatError
from robomodel.bag.model import Storage, TopicSummary
from robomodel.runtime.qos import Durability, QoSProfile, Reliability

__all__ = ["FileEntry", "read_metadata", "write_metadata"]

VERSION = 9
MAX_METADATA_BYTES = 4 << 20  # a bag of 1,000 topics and 1,000 files writes about 1 MB
MAX_BAG_FILES = 10_000  # a day split every 10 s
_INFINITE = {"sec": 9223372036, "nsec": 854775807}  # rmw's "unspecified" duration


@dataclass(frozen=True, slots=True)
class FileEntry:
    """One storage file of a rosbag2 folder, with its span and count."""

    path: str
    start_ns: int
    end_ns: int
    message_count: int


def _qos_dict(qos: QoSProfile) -> dict[str, Any]:
    return {
        "history": "keep_last",
        "depth": qos.depth,
        "reliability": qos.reliability.value,
        "durability": qos.durability.value,
        "deadline": dict(_INFINITE),
        "lifespan": dict(_INFINITE),
        "liveliness": "automatic",
        "liveliness_lease_duration": dict(_INFINITE),
        "avoid_ros_namespace_conventions": False,
    }


def qos_from_dict(entry: Mapping[str, Any]) -> QoSProfile:
    durability = Durability.TRANSIENT_LOCAL
    if str(entry.get("durability", "")).lower() != "transient_local":
        durability = Durability.VOLATILE
    reliability = Reliability.BEST_EFFORT
    if str(entry.get("reliability", "")).lower() != "best_effort":
        reliability = Reliability.RELIABLE
    return QoSProfile(int(entry.get("depth", 10) or 10), durability, reliability)


def write_metadata(
    folder: Path,
    storage: Storage,
    files: Sequence[FileEntry],
    topics: Sequence[tuple[TopicSummary, str]],
) -> None:
    """Write ``folder/metadata.yaml`` atomically. ``topics`` pairs a summary with its hash."""
    start = min((f.start_ns for f in files if f.message_count), default=0)
    end = max((f.end_ns for f in files if f.message_count), default=start)
    info = {
        "version": VERSION,
        "storage_identifier": storage.value,
        "duration": {"nanoseconds": end - start},
        "starting_time": {"nanoseconds_since_epoch": start},
        "message_count": sum(f.message_count for f in files),
        "topics_with_message_count": [
            {
                "topic_metadata": {
                    "name": topic.name,
                    "type": topic.type,
                    "serialization_format": topic.serialization_format,
                    "offered_qos_profiles": [_qos_dict(q) for q in topic.offered_qos],
                    "type_description_hash": digest,
                },
                "message_count": topic.count,
            }
            for topic, digest in topics
        ],
        "compression_format": "",
        "compression_mode": "",
        "relative_file_paths": [f.path for f in files],
        "files": [
            {
                "path": f.path,
                "starting_time": {"nanoseconds_since_epoch": f.start_ns},
                "duration": {"nanoseconds": f.end_ns - f.start_ns},
                "message_count": f.message_count,
            }
            for f in files
        ],
        "custom_data": {},
        "ros_distro": "jazzy",
    }
    text = yaml.safe_dump({"rosbag2_bagfile_information": info}, sort_keys=False)
    atomic_write_text(folder / "metadata.yaml", text)


@dataclass(frozen=True, slots=True)
class Metadata:
    storage: Storage
    files: tuple[str, ...]
    qos: dict[str, tuple[QoSProfile, ...]]
    ros_distro: str


def _offered(entry: Any) -> tuple[QoSProfile, ...]:
    if isinstance(entry, str):  # versions before 9 keep the list as a YAML string
        entry = load_yaml_data(entry, what="offered_qos_profiles") if entry.strip() else []
    if not isinstance(entry, list):
        return ()
    return tuple(qos_from_dict(q) for q in entry if isinstance(q, dict))


def _one_line(exc: yaml.YAMLError) -> str:
    """A YAML error as one line: where and what (PyYAML's text spans several lines)."""
    mark = getattr(exc, "problem_mark", None)
    where = f"line {mark.line + 1}, column {mark.column + 1}: " if mark is not None else ""
    problem = " ".join(filter(None, (getattr(exc, "context", None), getattr(exc, "problem", None))))
    return where + " ".join((problem or str(exc)).split())


def _file_list(path: Path, entries: Any) -> tuple[str, ...]:
    """The storage files named; a name yaml-cpp wrote unquoted may read back as a number."""
    if not isinstance(entries, list) or not all(isinstance(e, str | int) for e in entries):
        raise BagFormatError(str(path), "relative_file_paths is not a list of file names")
    if len(entries) > MAX_BAG_FILES:
        raise BagFormatError(
            str(path), f"{len(entries)} relative_file_paths; a bag has at most {MAX_BAG_FILES}"
        )
    return tuple(str(e) for e in entries)


def read_metadata(folder: Path) -> Metadata:
    """The parts of ``folder/metadata.yaml`` a reader needs; BagFormatError if it is bad."""
    path = folder / "metadata.yaml"
    try:
        text = read_user_text(path, what="bag metadata", limit=MAX_METADATA_BYTES)
        info = load_yaml_data(text, what=str(path))["rosbag2_bagfile_information"]
        storage = Storage(str(info.get("storage_identifier") or "sqlite3"))
        files = _file_list(path, info.get("relative_file_paths") or ())
        qos = {
            str(t["topic_metadata"]["name"]): _offered(
                t["topic_metadata"].get("offered_qos_profiles")
            )
            for t in info.get("topics_with_message_count") or ()
        }
    except UserFileError as exc:
        reason = exc.reason
        if exc.too_large:
            size_mib = path.stat().st_size / 2**20
            reason = (
                f"{size_mib:.1f} MiB; at most {MAX_METADATA_BYTES >> 20} MiB of bag metadata is "
                "read (rosbag2 writes a few kB)"
            )
        raise BagFormatError(str(path), reason) from None
    except YamlNestingError as exc:
        raise BagFormatError(str(path), str(exc).removeprefix(f"{path}: ")) from None
    except yaml.YAMLError as exc:
        raise BagFormatError(str(path), f"not a rosbag2 metadata file ({_one_line(exc)})") from None
    except (OSError, KeyError, TypeError, ValueError, AttributeError) as exc:
        raise BagFormatError(str(path), f"not a rosbag2 metadata file ({exc})") from None
    inside = folder.resolve()
    for name in files:
        if not (folder / name).resolve().is_relative_to(inside):
            raise BagFormatError(
                str(path), f"file '{name}' is outside the bag folder; a bag lists its own files"
            )
    return Metadata(storage, files, qos, str(info.get("ros_distro") or ""))
