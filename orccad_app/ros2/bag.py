"""``orccad run --trace DIR --trace-format rosbag2``: a rosbag2 directory of the run.

:class:`Rosbag2TraceWriter` is a :class:`~orccad_app.trace.mcap_writer.TopicWriter` (the same
topics as the MCAP trace, fed by the same recorder) whose sink is ``rosbags``'s rosbag2 writer:
format version 9, MCAP storage, CDR serialization, each connection with its ROS 2 Jazzy type
and RIHS01 hash. Each JSON topic becomes a ROS 2 topic of the type
:func:`~orccad_app.ros2.messages.ros_type` gives (``/log`` is ``/rosout``); besides:

- ``/joint_states`` — ``sensor_msgs/msg/JointState``: at each instant a module reads a robot's
  sensor, the robot's hinge and slide joints (MJCF names) from the plant's state: ``position``
  [rad], ``velocity`` [rad/s], ``effort`` the actuator force [N·m] applied over the last
  integration step;
- ``/<robot>/pose`` — ``geometry_msgs/msg/PoseStamped`` in ``world``: a floating base (the
  AUV's hull), with the frames.

A bag's timestamps (and every ``header.stamp``) are the simulated instants [ns]. The bag's
``custom_data`` holds the run's description (``orccad.mission``, ``orccad.file``,
``orccad.seed``). ``ros2 bag info DIR`` and ``ros2 bag play DIR`` read it; here it is read
back with ``rosbags`` (``tests/ros2``).
"""

from __future__ import annotations

import json
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from orccad_app.diagnostics import OrccadError
from orccad_app.ros2 import messages
from orccad_app.trace.mcap_writer import TopicWriter
from orccad_app.trace.scene import Transform

__all__ = ["Rosbag2TraceWriter"]

_TOPICS = {"/log": "/rosout"}
"""JSON topics renamed in a bag (ROS 2's conventions)."""


class _Connection:
    __slots__ = ("connection", "msgtype")

    def __init__(self, connection: Any, msgtype: str) -> None:
        self.connection, self.msgtype = connection, msgtype


class Rosbag2TraceWriter(TopicWriter):
    """The run's topics as a rosbag2 directory ``path`` (created: it must not exist)."""

    wants_joint_states = True

    def __init__(self, path: str | Path, metadata: Mapping[str, str] | None = None,
                 sensors: Mapping[tuple[str, str], str] | None = None) -> None:
        from rosbags.rosbag2 import StoragePlugin, Writer
        from rosbags.rosbag2.errors import WriterError

        self.path = str(path)
        if Path(path).exists():
            raise OrccadError(f"--trace {path}: exists already (a rosbag2 trace is a new "
                              f"directory)")
        self._store = messages.typestore()
        self._writer = Writer(path, version=9, storage_plugin=StoragePlugin.MCAP)
        for key, value in (metadata or {}).items():
            self._writer.set_custom_data(f"orccad.{key}", str(value))
        try:
            self._writer.open()
        except (WriterError, OSError) as error:
            raise OrccadError(f"cannot write the trace {path}: {error}") from None
        self._extra: dict[str, _Connection] = {}
        super().__init__(metadata, sensors)

    def _connection(self, topic: str, msgtype: str) -> _Connection:
        connection = self._writer.add_connection(topic, msgtype, typestore=self._store)
        return _Connection(connection, msgtype)

    def _register(self, topic: str, name: str, schema: str, latched: bool) -> Any:
        msgtype = messages.ros_type(name, json.loads(schema))
        if msgtype is None:
            return None
        return self._connection(_TOPICS.get(topic, topic), msgtype)

    def _write(self, channel: _Connection, time_ns: int, message: Any) -> None:
        self._writer.write(channel.connection, time_ns,
                           self._store.serialize_cdr(message, channel.msgtype))

    def _publish(self, channel: Any, time_ns: int, body: bytes, sequence: int) -> None:
        if channel is not None:
            self._write(channel, time_ns, messages.from_json(channel.msgtype, json.loads(body)))

    def _topic(self, topic: str, msgtype: str) -> _Connection:
        found = self._extra.get(topic)
        if found is None:
            found = self._extra[topic] = self._connection(topic, msgtype)
        return found

    def joint_state(self, time_ns: int, robot: str, names: tuple[str, ...],
                    position: list[float], velocity: list[float],
                    effort: list[float]) -> None:
        """``/joint_states``: the robot's joints at ``time_ns``."""
        self._write(self._topic("/joint_states", "sensor_msgs/msg/JointState"), time_ns,
                    messages.joint_state(time_ns, names, position, velocity, effort))

    def pose(self, time_ns: int, robot: str, transform: Transform) -> None:
        """``/<robot>/pose``: the floating base's pose in ``world``."""
        self._write(self._topic(f"/{robot}/pose", "geometry_msgs/msg/PoseStamped"), time_ns,
                    messages.pose_stamped(time_ns, transform.parent_id, transform.translation,
                                          transform.rotation))

    def _finish(self) -> None:
        self._writer.close()
