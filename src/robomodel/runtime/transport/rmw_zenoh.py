"""rmw_zenoh's wire format (Jazzy 0.2.4 and later): key expressions, liveliness tokens, QoS
strings, entity GIDs and attachments. Pure functions, no Zenoh session.

Transcribed from ros2/rmw_zenoh ``rmw_zenoh_cpp/src/detail``:

- ``liveliness_utils.cpp`` — ``TopicInfo`` (data keys ``<domain>/<name without the outer
  slashes>/<DDS type>/<type hash>``), ``Entity`` (tokens ``@ros2_lv/<domain>/<zid>/<nid>/<id>/
  <NN|MP|MS|SS|SC>/<enclave>/<namespace>/<node>[/<name>/<type>/<hash>/<qos>]`` with ``/``
  mangled to ``%``; a part may not be empty), ``qos_to_keyexpr`` / ``keyexpr_to_qos`` (fields
  equal to rmw_zenoh's default QoS are left empty) and the GID: XXH3-128 of the token, its low
  then its high 64 bits in little-endian order.
- ``qos.cpp`` — the default QoS: keep last 42, reliable, volatile, infinite durations,
  automatic liveliness.
- ``attachment_helpers.cpp`` (0.2.4, "Change serialization format", PR #601) — the attachment
  of every sample, request and reply: int64 sequence number, int64 source timestamp [ns since
  the epoch], then the 16-byte GID as a zenoh-ext array (LEB128 length 16 and the bytes): 33
  bytes, little-endian. Before 0.2.4 (and in Humble's 0.1.0 and 0.1.1) each value was preceded
  by its name as a zenoh-ext string; :func:`parse_attachment` reads that form too.
"""

from __future__ import annotations

import enum
import struct
from dataclasses import dataclass, replace
from typing import NamedTuple

from robomodel.runtime.transport._zenoh_qos import qos_from_key, qos_to_key

__all__ = [
    "ADMIN_SPACE",
    "ATTACHMENT_SIZE",
    "Attachment",
    "EntityKind",
    "EntityToken",
    "demangle",
    "encode_attachment",
    "entity_gid",
    "mangle",
    "parse_attachment",
    "qos_from_key",
    "qos_to_key",
    "topic_key",
]

ADMIN_SPACE = "@ros2_lv"
GID_SIZE = 16
ATTACHMENT_SIZE = 8 + 8 + 1 + GID_SIZE
_ATTACHMENT = struct.Struct("<qqB16s")


class EntityKind(enum.Enum):
    NODE = "NN"
    PUBLISHER = "MP"
    SUBSCRIPTION = "MS"
    SERVICE = "SS"
    CLIENT = "SC"


def mangle(name: str) -> str:
    return name.replace("/", "%")


def demangle(text: str) -> str:
    return text.replace("%", "/")


def topic_key(domain_id: int, name: str, dds_type: str, type_hash: str) -> str:
    """The key of a topic's samples or a service's queries (``TopicInfo``)."""
    return f"{domain_id}/{name.strip('/')}/{dds_type}/{type_hash}"


def _stoul(text: str) -> int | None:
    """C++'s ``std::stoul`` (``Entity::make`` reads the domain id so): leading blanks, a
    sign, decimal digits, anything after them ignored; None where it throws."""
    rest = text.lstrip(" \t\n\v\f\r")
    negative = rest[:1] == "-"
    rest = rest[1:] if rest[:1] in ("+", "-") else rest
    digits = len(rest) - len(rest.lstrip("0123456789"))
    if digits == 0 or int(rest[:digits]) > 2**64 - 1:
        return None
    value = int(rest[:digits])
    return (-value) % 2**64 if negative else value


# -- liveliness tokens -------------------------------------------------------------------------


@dataclass(frozen=True, slots=True)
class EntityToken:
    """One entity of the ROS graph as its liveliness token names it."""

    domain_id: int
    zid: str
    node_id: int | str  # rmw_zenoh's are decimal numbers; a peer's are read as they are
    entity_id: int | str
    kind: EntityKind
    namespace: str
    node_name: str
    enclave: str = "/"
    name: str = ""
    dds_type: str = ""
    type_hash: str = ""
    qos: str = ""

    @property
    def node(self) -> str:
        """The node's fully qualified name."""
        return f"{self.namespace.rstrip('/')}/{self.node_name}"

    def key(self) -> str:
        parts = [
            ADMIN_SPACE,
            str(self.domain_id),
            self.zid,
            str(self.node_id),
            str(self.entity_id),
            self.kind.value,
            mangle(self.enclave),
            mangle(self.namespace),
            mangle(self.node_name),
        ]
        if self.kind is not EntityKind.NODE:
            parts += [mangle(self.name), mangle(self.dds_type), mangle(self.type_hash), self.qos]
        return "/".join(parts)

    @classmethod
    def parse(cls, key: str) -> EntityToken | None:
        """The entity of a token; None where ``Entity::make`` refuses it. As there, parts past
        the last one used are ignored, node and entity ids are taken as they are (decimal
        ones as numbers), and the domain id is read by ``std::stoul``."""
        parts = key.split("/")
        if len(parts) < 9 or parts[0] != ADMIN_SPACE or not all(parts):
            return None
        try:
            kind = EntityKind(parts[5])
        except ValueError:
            return None
        domain_id = _stoul(parts[1])
        if domain_id is None:
            return None
        node_id, entity_id = (int(p) if p.isascii() and p.isdigit() else p for p in parts[3:5])
        token = cls(domain_id, parts[2], node_id, entity_id, kind, demangle(parts[7]),
                    demangle(parts[8]), demangle(parts[6]))  # fmt: skip
        if kind is EntityKind.NODE:
            return token
        if len(parts) < 13 or qos_from_key(parts[12]) is None:
            return None
        return replace(token, name=demangle(parts[9]), dds_type=demangle(parts[10]),
                       type_hash=demangle(parts[11]), qos=parts[12])  # fmt: skip


def entity_gid(token_key: str) -> bytes:
    """The 16-byte GID rmw_zenoh derives from an entity's token (XXH3-128, low then high)."""
    import xxhash

    return int(xxhash.xxh3_128_intdigest(token_key.encode("utf-8"))).to_bytes(16, "little")


# -- attachments --------------------------------------------------------------------------------


class Attachment(NamedTuple):  # a tuple: built for every sample, in half a dataclass's time
    sequence_number: int
    source_timestamp_ns: int
    gid: bytes


def encode_attachment(sequence_number: int, source_timestamp_ns: int, gid: bytes) -> bytes:
    return _ATTACHMENT.pack(sequence_number, source_timestamp_ns, GID_SIZE, gid)


def _legacy(data: bytes) -> Attachment | None:
    """The labelled form of rmw_zenoh before 0.2.4: each value after its name."""
    numbers: list[int] = []
    gid = b""
    offset = 0
    for label, size in ((b"sequence_number", 8), (b"source_timestamp", 8), (b"source_gid", 0)):
        if data[offset : offset + 1 + len(label)] != bytes([len(label)]) + label:
            return None
        offset += 1 + len(label)
        if size:
            if offset + 8 > len(data):
                return None
            numbers.append(struct.unpack_from("<q", data, offset)[0])
            offset += 8
        else:
            if data[offset : offset + 1] != bytes([GID_SIZE]) or len(data) != offset + 1 + GID_SIZE:
                return None
            gid = bytes(data[offset + 1 :])
    return Attachment(numbers[0], numbers[1], gid)


def parse_attachment(data: bytes) -> Attachment | None:
    """The attachment, or None when it is absent or not exactly one of rmw_zenoh's forms."""
    if len(data) == ATTACHMENT_SIZE and data[16] == GID_SIZE:
        seq, stamp, _, gid = _ATTACHMENT.unpack(data)
        return Attachment(seq, stamp, gid)
    if 40 < len(data) < 128:
        return _legacy(data)
    return None
