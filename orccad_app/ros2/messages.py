"""ROS 2 messages built with ``rosbags``'s type store of ROS 2 Jazzy (CDR, RIHS01 type hashes).

Every stamp is the simulated instant (``builtin_interfaces/Time``: ``sec``, ``nanosec``). The
trace's JSON topics (:mod:`orccad_app.trace.mcap_writer`) map to ROS 2 types by their schema
(:func:`ros_type`, :func:`from_json`):

==========================  ==============================  ===================================
JSON schema                 ROS 2 type                      fields
==========================  ==============================  ===================================
``foxglove.Log``            ``rcl_interfaces/msg/Log``      on ``/rosout``; levels 10-50
``foxglove.FrameTransforms`` ``tf2_msgs/msg/TFMessage``     on ``/tf``
``orccad.PortValue``        ``std_msgs/msg/Float64MultiArray`` a number or a vector as ``data``
                            or ``std_msgs/msg/String``      (a text port)
``orccad.Active``,          ``std_msgs/msg/Int8``           ``data``: 0/1, the phase, the
``orccad.Phase``,                                           verdict (1, 0, -1)
``orccad.Verdict``
anything else               ``std_msgs/msg/String``         ``data``: the JSON message
==========================  ==============================  ===================================

``foxglove.SceneUpdate`` has no ROS 2 message here (ROS describes a robot by its URDF on
``/robot_description``, which MJCF is not): it is left out of a bag.
"""

from __future__ import annotations

import json
from functools import cache
from typing import Any

import numpy as np

__all__ = ["typestore", "type_hash", "time_msg", "joint_state", "tf_message", "pose_stamped",
           "log_message", "ros_type", "from_json", "ROS_DISTRIBUTION", "ROS_LEVELS"]

ROS_DISTRIBUTION = "jazzy"
"""The ROS 2 distribution whose message definitions (and type hashes) are used."""

ROS_LEVELS = {0: 0, 1: 10, 2: 20, 3: 30, 4: 40, 5: 50}
"""``foxglove.Log`` level -> ``rcl_interfaces/msg/Log`` level (DEBUG 10 … FATAL 50)."""


@cache
def typestore() -> Any:
    """``rosbags``'s type store of ROS 2 Jazzy."""
    from rosbags.typesys import Stores, get_typestore

    return get_typestore(Stores.ROS2_JAZZY)


@cache
def type_hash(msgtype: str) -> str:
    """The RIHS01 type hash of ``msgtype`` (``RIHS01_…``, REP 2011)."""
    return str(typestore().hash_rihs01(msgtype))


def _type(name: str) -> Any:
    return typestore().types[name]


def time_msg(time_ns: int) -> Any:
    """``builtin_interfaces/msg/Time`` of ``time_ns``."""
    return _type("builtin_interfaces/msg/Time")(sec=time_ns // 1_000_000_000,
                                                nanosec=time_ns % 1_000_000_000)


def _header(time_ns: int, frame_id: str) -> Any:
    return _type("std_msgs/msg/Header")(stamp=time_msg(time_ns), frame_id=frame_id)


def joint_state(time_ns: int, names: tuple[str, ...], position: list[float],
                velocity: list[float], effort: list[float]) -> Any:
    """``sensor_msgs/msg/JointState`` [rad, rad/s, N·m]."""
    return _type("sensor_msgs/msg/JointState")(
        header=_header(time_ns, ""), name=list(names),
        position=np.asarray(position, dtype=np.float64),
        velocity=np.asarray(velocity, dtype=np.float64),
        effort=np.asarray(effort, dtype=np.float64))


def _vector3(x: float, y: float, z: float) -> Any:
    return _type("geometry_msgs/msg/Vector3")(x=x, y=y, z=z)


def _quaternion(values: dict[str, float]) -> Any:
    return _type("geometry_msgs/msg/Quaternion")(**{k: values[k] for k in "xyzw"})


def tf_message(message: dict[str, Any]) -> Any:
    """``tf2_msgs/msg/TFMessage`` of a ``foxglove.FrameTransforms`` message."""
    stamped = _type("geometry_msgs/msg/TransformStamped")
    transform = _type("geometry_msgs/msg/Transform")
    found = []
    for t in message["transforms"]:
        time_ns = t["timestamp"]["sec"] * 1_000_000_000 + t["timestamp"]["nsec"]
        found.append(stamped(header=_header(time_ns, t["parent_frame_id"]),
                             child_frame_id=t["child_frame_id"],
                             transform=transform(translation=_vector3(**t["translation"]),
                                                 rotation=_quaternion(t["rotation"]))))
    return _type("tf2_msgs/msg/TFMessage")(transforms=found)


def pose_stamped(time_ns: int, frame_id: str, translation: tuple[float, float, float],
                 rotation: tuple[float, float, float, float]) -> Any:
    """``geometry_msgs/msg/PoseStamped`` in ``frame_id`` (rotation ``x, y, z, w``)."""
    pose = _type("geometry_msgs/msg/Pose")(
        position=_type("geometry_msgs/msg/Point")(x=translation[0], y=translation[1],
                                                  z=translation[2]),
        orientation=_quaternion(dict(zip("xyzw", rotation))))
    return _type("geometry_msgs/msg/PoseStamped")(header=_header(time_ns, frame_id), pose=pose)


def log_message(message: dict[str, Any]) -> Any:
    """``rcl_interfaces/msg/Log`` of a ``foxglove.Log`` message (``name``: ``orccad.<name>``)."""
    stamp = message["timestamp"]
    return _type("rcl_interfaces/msg/Log")(
        stamp=_type("builtin_interfaces/msg/Time")(sec=stamp["sec"], nanosec=stamp["nsec"]),
        level=ROS_LEVELS.get(message["level"], 0), name=f"orccad.{message['name']}",
        msg=message["message"], file=message["file"], function="", line=message["line"])


def float64_array(values: Any) -> Any:
    """``std_msgs/msg/Float64MultiArray`` holding ``values`` (a number: one element)."""
    data = np.atleast_1d(np.asarray(values, dtype=np.float64))
    layout = _type("std_msgs/msg/MultiArrayLayout")(dim=[], data_offset=0)
    return _type("std_msgs/msg/Float64MultiArray")(layout=layout, data=data)


def ros_type(schema_name: str, schema: dict[str, Any]) -> str | None:
    """The ROS 2 type of a JSON topic (see the module docstring); ``None``: left out."""
    if schema_name == "foxglove.Log":
        return "rcl_interfaces/msg/Log"
    if schema_name == "foxglove.FrameTransforms":
        return "tf2_msgs/msg/TFMessage"
    if schema_name == "foxglove.SceneUpdate":
        return None
    if schema_name == "orccad.PortValue":
        kind = schema["properties"]["value"].get("type")
        return "std_msgs/msg/String" if kind == "string" else "std_msgs/msg/Float64MultiArray"
    if schema_name in ("orccad.Active", "orccad.Phase", "orccad.Verdict"):
        return "std_msgs/msg/Int8"
    return "std_msgs/msg/String"


def from_json(msgtype: str, message: dict[str, Any]) -> Any:
    """The ROS 2 message of type ``msgtype`` (:func:`ros_type`) of a JSON ``message``."""
    if msgtype == "rcl_interfaces/msg/Log":
        return log_message(message)
    if msgtype == "tf2_msgs/msg/TFMessage":
        return tf_message(message)
    if msgtype == "std_msgs/msg/Float64MultiArray":
        return float64_array(message["value"])
    if msgtype == "std_msgs/msg/Int8":
        return _type("std_msgs/msg/Int8")(data=int(message["value"]))
    if "value" in message and isinstance(message["value"], str) and len(message) == 1:
        return _type("std_msgs/msg/String")(data=message["value"])
    return _type("std_msgs/msg/String")(data=json.dumps(message, separators=(",", ":")))
