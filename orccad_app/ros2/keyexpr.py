"""rmw_zenoh's wire conventions for ROS 2 topics over Zenoh (as ``rmw_zenoh_cpp`` does them).

- **Key expression** of a topic's data: ``<domain_id>/<topic>/<type>/<hash>`` — the topic's
  fully qualified name without its leading (and trailing) ``/`` (inner ``/`` kept), the type
  in DDS-mangled form ``<package>::msg::dds_::<Name>_`` and its RIHS01 hash
  (``0/joint_states/sensor_msgs::msg::dds_::JointState_/RIHS01_a13e…``);
- **payload**: the message in CDR with its 4-byte encapsulation header;
- **attachment**: Zenoh's serialization of ``"sequence_number"``, an int64, ``"source_timestamp"``,
  an int64 [ns], ``"source_gid"`` and 16 bytes (a string or a byte buffer is its length as an
  unsigned LEB128 varint then its bytes; an int64 is 8 little-endian bytes).

:func:`attachment` and :func:`read_attachment` write and read the latter.

- **Liveliness tokens** (ROS 2 discovery: what ``ros2 node list`` and ``ros2 topic list``
  show), :func:`liveliness_key`: ``@ros2_lv/<domain>/<zid>/<node id>/<entity id>/<kind>/
  <enclave>/<namespace>/<node>`` for a node (kind ``NN``), followed by ``/<topic>/<type>/
  <hash>/<qos>`` for a publisher (``MP``) or a subscription (``MS``); every ``/`` inside a
  name is written ``%`` (the root namespace and enclave ``/`` are ``%``); ``<qos>`` lists
  reliability, durability, history and depth, deadline, lifespan and liveliness, each left
  empty where it is the default profile's (``::,:,:,:,,`` for the default profile).
"""

from __future__ import annotations

import struct
from dataclasses import dataclass
from enum import Enum

from orccad_app.diagnostics import OrccadError

__all__ = ["topic_key", "dds_type", "Attachment", "attachment", "read_attachment", "GID_SIZE",
           "EntityKind", "liveliness_key", "LIVELINESS_SPACE", "DEFAULT_QOS"]

GID_SIZE = 16
"""Bytes of a publisher's global id (``RMW_GID_STORAGE_SIZE``)."""


def dds_type(msgtype: str) -> str:
    """``sensor_msgs/msg/JointState`` -> ``sensor_msgs::msg::dds_::JointState_``."""
    package, kind, name = msgtype.split("/")
    return f"{package}::{kind}::dds_::{name}_"


def topic_key(domain_id: int, topic: str, msgtype: str, type_hash: str) -> str:
    """The key expression of ``topic``'s data (see the module docstring)."""
    name = topic[1:] if topic.startswith("/") else topic
    name = name[:-1] if name.endswith("/") else name
    return f"{domain_id}/{name}/{dds_type(msgtype)}/{type_hash}"


LIVELINESS_SPACE = "@ros2_lv"
"""The admin space of rmw_zenoh's liveliness tokens."""

DEFAULT_QOS = "::,:,:,:,,"
"""The ``<qos>`` part of a token for the default QoS profile (reliable, volatile, keep last
10, no deadline, lifespan or liveliness lease): every field left empty."""


class EntityKind(Enum):
    """What a liveliness token announces."""

    NODE = "NN"
    PUBLISHER = "MP"
    SUBSCRIPTION = "MS"


def _mangled(name: str) -> str:
    return name.replace("/", "%")


def liveliness_key(domain_id: int, zid: str, node_id: int, entity_id: int, kind: EntityKind,
                   node: str, *, namespace: str = "/", enclave: str = "/",
                   topic: str | None = None, msgtype: str | None = None,
                   type_hash: str | None = None, qos: str = DEFAULT_QOS) -> str:
    """The key of the liveliness token of a node (``topic`` ``None``) or of one of its
    publishers or subscriptions (see the module docstring)."""
    parts = [LIVELINESS_SPACE, str(domain_id), zid, str(node_id), str(entity_id), kind.value,
             _mangled(enclave), _mangled(namespace), _mangled(node)]
    if kind is not EntityKind.NODE:
        if topic is None or msgtype is None or type_hash is None:
            raise ValueError("a publisher's or subscription's token names its topic, type "
                             "and type hash")
        parts += [_mangled(topic), dds_type(msgtype), type_hash, qos]
    return "/".join(parts)


@dataclass(frozen=True)
class Attachment:
    """What rmw_zenoh attaches to a message: its publisher's sequence number, the source
    timestamp [ns] and the publisher's global id."""

    sequence_number: int
    source_timestamp_ns: int
    source_gid: bytes


def _varint(value: int) -> bytes:
    out = bytearray()
    while True:
        byte = value & 0x7F
        value >>= 7
        if value:
            out.append(byte | 0x80)
        else:
            out.append(byte)
            return bytes(out)


def _chunk(data: bytes) -> bytes:
    return _varint(len(data)) + data


def attachment(sequence_number: int, source_timestamp_ns: int, gid: bytes) -> bytes:
    """The attachment's bytes."""
    if len(gid) != GID_SIZE:
        raise ValueError(f"a gid has {GID_SIZE} bytes, got {len(gid)}")
    return (_chunk(b"sequence_number") + struct.pack("<q", sequence_number)
            + _chunk(b"source_timestamp") + struct.pack("<q", source_timestamp_ns)
            + _chunk(b"source_gid") + _chunk(gid))


class _Reader:
    def __init__(self, data: bytes) -> None:
        self.data, self.at = data, 0

    def varint(self) -> int:
        value, shift = 0, 0
        while True:
            if self.at >= len(self.data) or shift > 63:
                raise OrccadError("a malformed rmw_zenoh attachment (varint)")
            byte = self.data[self.at]
            self.at += 1
            value |= (byte & 0x7F) << shift
            shift += 7
            if not byte & 0x80:
                return value

    def take(self, count: int) -> bytes:
        if self.at + count > len(self.data):
            raise OrccadError("a malformed rmw_zenoh attachment (truncated)")
        found = self.data[self.at:self.at + count]
        self.at += count
        return found

    def key(self, expected: bytes) -> None:
        if self.take(self.varint()) != expected:
            raise OrccadError(f"a malformed rmw_zenoh attachment (no {expected.decode()})")


def read_attachment(data: bytes) -> Attachment:
    """The :class:`Attachment` of ``data`` (an :class:`OrccadError` if malformed)."""
    reader = _Reader(bytes(data))
    reader.key(b"sequence_number")
    sequence = struct.unpack("<q", reader.take(8))[0]
    reader.key(b"source_timestamp")
    stamp = struct.unpack("<q", reader.take(8))[0]
    reader.key(b"source_gid")
    gid = reader.take(reader.varint())
    if len(gid) != GID_SIZE:
        raise OrccadError(f"a malformed rmw_zenoh attachment (a gid of {len(gid)} bytes)")
    return Attachment(sequence, stamp, gid)
