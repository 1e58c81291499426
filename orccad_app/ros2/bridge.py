"""``--ros2-zenoh`` (experimental): the plant and the mission as ROS 2 topics over Zenoh.

:class:`ZenohBridge` is the reusable piece (``orccad run`` and ``orccad sil`` use it): one
Zenoh session in *peer* mode that connects to the given endpoints only — no multicast or
gossip scouting — and speaks rmw_zenoh's conventions (:mod:`.keyexpr`: key expressions, CDR
payloads, attachments) in ROS domain ``domain_id``:

- ``/joint_states`` — published: ``sensor_msgs/msg/JointState`` of a robot
  (:meth:`ZenohBridge.joint_states`), as ``topic_based_ros2_control``'s hardware interface
  reads them;
- ``/joint_commands`` — subscribed: ``sensor_msgs/msg/JointState`` commands as
  ``topic_based_ros2_control`` publishes them; :meth:`ZenohBridge.commands` drains those
  received (their ``effort`` [N·m], by joint name);
- ``/orccad/input/<Name>`` — subscribed: a mission input (``std_msgs/msg/Empty`` for a pure
  one, ``Bool``, ``Int64``, ``Float64`` or ``Float64MultiArray`` for a valued one);
  :meth:`ZenohBridge.inputs` drains them;
- ``/orccad/output/<Name>`` — published: a mission output, same types
  (:meth:`ZenohBridge.output`).

The session announces itself as rmw_zenoh does, with liveliness tokens
(:func:`~orccad_app.ros2.keyexpr.liveliness_key`): node :data:`NODE_NAME`, then each of its
subscriptions when declared and each publisher when first used, so that ROS 2's graph
(``ros2 node list``, ``ros2 topic list``) sees them; they are undeclared with the session.

Messages arrive on Zenoh's threads and wait in queues until the caller drains them on its own
thread (the executive's): nothing from outside touches the run between two events.

:class:`MissionBridge` is ``orccad run``'s observer: joint states at each instant a module
reads a robot's sensors, the commands' efforts written to the robot's actuators at the next
reaction (until a Module-Task writes them again), the inputs raised in the mission, its
outputs published.
"""

from __future__ import annotations

import os
import queue
import secrets
import time
from dataclasses import dataclass
from typing import Any

import numpy as np

from orccad_app.diagnostics import OrccadError
from orccad_app.mission.observer import MissionObserver
from orccad_app.ros2 import messages
from orccad_app.ros2.endpoint import zenoh_reason
from orccad_app.ros2.keyexpr import EntityKind, attachment, liveliness_key, topic_key

__all__ = ["ZenohBridge", "MissionBridge", "JointCommand", "DEFAULT_ENDPOINT", "VALUE_TYPES",
           "session_config", "NODE_NAME"]

DEFAULT_ENDPOINT = "tcp/127.0.0.1:7447"
"""rmw_zenoh's router (``ros2 run rmw_zenoh_cpp rmw_zenohd``) on this machine."""

VALUE_TYPES = {None: "std_msgs/msg/Empty", "bool": "std_msgs/msg/Bool",
               "int": "std_msgs/msg/Int64", "float": "std_msgs/msg/Float64",
               "duration": "std_msgs/msg/Float64", "vector": "std_msgs/msg/Float64MultiArray"}
"""A mission signal's type -> its ROS 2 message type."""

NODE_NAME = "orccad"
"""The ROS 2 node the bridge announces (namespace ``/``)."""

REACH_LOOK_S = 1.0
"""How often the bridge looks whether a router or peer is connected, at most [wall s]."""


@dataclass(frozen=True)
class JointCommand:
    """A ``/joint_commands`` message received: ``effort`` [N·m] by joint name."""

    effort: dict[str, float]


def session_config(connect: list[str], listen: list[str] = ()) -> Any:  # type: ignore[assignment]
    """A Zenoh peer configuration on the given endpoints only: no multicast scouting, no
    gossip (nothing leaves the endpoints named)."""
    import json

    import zenoh

    config = zenoh.Config()
    config.insert_json5("mode", '"peer"')
    config.insert_json5("connect/endpoints", json.dumps(list(connect)))
    config.insert_json5("listen/endpoints", json.dumps(list(listen)))
    config.insert_json5("scouting/multicast/enabled", "false")
    config.insert_json5("scouting/gossip/enabled", "false")
    return config


def _value(msgtype: str, message: Any) -> Any:
    if msgtype == "std_msgs/msg/Empty":
        return None
    if msgtype == "std_msgs/msg/Float64MultiArray":
        return [float(v) for v in message.data]
    return message.data


def _message(msgtype: str, value: Any) -> Any:
    store = messages.typestore()
    kind = store.types[msgtype]
    if msgtype == "std_msgs/msg/Empty":
        return kind(structure_needs_at_least_one_member=0)
    if msgtype == "std_msgs/msg/Float64MultiArray":
        return messages.float64_array(value)
    if msgtype == "std_msgs/msg/Bool":
        return kind(data=bool(value))
    if msgtype == "std_msgs/msg/Int64":
        return kind(data=int(value))
    return kind(data=float(value))


class ZenohBridge:
    """A Zenoh session speaking rmw_zenoh (see the module docstring).

    :param connect: endpoints to connect to (``tcp/127.0.0.1:7447``).
    :param inputs: the mission's inputs ``name -> type`` (``None``: pure).
    :param outputs: the mission's outputs, likewise.
    :param domain_id: the ROS domain (default ``ROS_DOMAIN_ID`` or 0).
    """

    def __init__(self, connect: list[str], inputs: dict[str, str | None],
                 outputs: dict[str, str | None], domain_id: int | None = None,
                 listen: list[str] = ()) -> None:  # type: ignore[assignment]
        import zenoh

        self.domain_id = int(os.environ.get("ROS_DOMAIN_ID", "0")) if domain_id is None \
            else domain_id
        try:
            self._session = zenoh.open(session_config(connect, listen))
        except Exception as error:  # zenoh.ZError: the reason from Zenoh
            raise OrccadError(f"--ros2-zenoh {' '.join([*connect, *listen])}: cannot open a "
                              f"Zenoh session: {zenoh_reason(error)}") from None
        self._reached = False
        self._next_look = 0.0
        self._closed = False
        self._store = messages.typestore()
        self._zid = str(self._session.info.zid())
        self._entities = 0  # ids of the node's entities (the node is 0)
        self._tokens = [self._session.liveliness().declare_token(liveliness_key(
            self.domain_id, self._zid, 0, 0, EntityKind.NODE, NODE_NAME))]
        self._gid = secrets.token_bytes(16)
        self._sequence = 0
        self._publishers: dict[str, tuple[Any, str]] = {}
        self._commands: queue.Queue[JointCommand] = queue.Queue()
        self._inputs: queue.Queue[tuple[str, Any]] = queue.Queue()
        self._outputs = dict(outputs)
        self._subscribers = [self._subscribe("/joint_commands", "sensor_msgs/msg/JointState",
                                             self._on_command)]
        for name, kind in inputs.items():
            msgtype = VALUE_TYPES.get(kind, "std_msgs/msg/Float64")
            self._subscribers.append(self._subscribe(
                f"/orccad/input/{name}", msgtype,
                lambda message, name=name, msgtype=msgtype:
                    self._inputs.put((name, _value(msgtype, message)))))

    def reached(self) -> bool:
        """Whether a Zenoh router or peer has been connected to since the session opened
        (looked at once per wall second at most: the answer costs a call into Zenoh)."""
        now = time.monotonic()
        if not self._reached and self._session is not None and now >= self._next_look:
            self._next_look = now + REACH_LOOK_S
            info = self._session.info
            self._reached = bool(list(info.routers_zid()) or list(info.peers_zid()))
        return self._reached

    def key(self, topic: str, msgtype: str) -> str:
        """The key expression of ``topic`` (rmw_zenoh's)."""
        return topic_key(self.domain_id, topic, msgtype, messages.type_hash(msgtype))

    def _announce(self, kind: EntityKind, topic: str, msgtype: str) -> None:
        """Declare the liveliness token of a publisher or subscription of ``topic``."""
        self._entities += 1
        self._tokens.append(self._session.liveliness().declare_token(liveliness_key(
            self.domain_id, self._zid, 0, self._entities, kind, NODE_NAME, topic=topic,
            msgtype=msgtype, type_hash=messages.type_hash(msgtype))))

    def _subscribe(self, topic: str, msgtype: str, handle: Any) -> Any:
        store = self._store
        self._announce(EntityKind.SUBSCRIPTION, topic, msgtype)

        def received(sample: Any) -> None:
            try:
                handle(store.deserialize_cdr(sample.payload.to_bytes(), msgtype))
            except Exception:  # a malformed message from outside: dropped, never raised
                return
        return self._session.declare_subscriber(self.key(topic, msgtype), received)

    def _on_command(self, message: Any) -> None:
        efforts = dict(zip(message.name, (float(v) for v in message.effort)))
        self._commands.put(JointCommand(efforts))

    def publish(self, topic: str, msgtype: str, message: Any, time_ns: int) -> None:
        """``message`` on ``topic`` (CDR, rmw_zenoh's attachment stamped ``time_ns``)."""
        found = self._publishers.get(topic)
        if found is None:
            self._announce(EntityKind.PUBLISHER, topic, msgtype)
            found = self._publishers[topic] = (
                self._session.declare_publisher(self.key(topic, msgtype)), msgtype)
        self._sequence += 1
        found[0].put(bytes(self._store.serialize_cdr(message, msgtype)),
                     attachment=attachment(self._sequence, time_ns, self._gid))

    def joint_states(self, time_ns: int, names: tuple[str, ...], position: list[float],
                     velocity: list[float], effort: list[float]) -> None:
        """``/joint_states``."""
        self.publish("/joint_states", "sensor_msgs/msg/JointState",
                     messages.joint_state(time_ns, names, position, velocity, effort), time_ns)

    def output(self, time_ns: int, name: str, value: Any) -> None:
        """``/orccad/output/<name>``."""
        msgtype = VALUE_TYPES.get(self._outputs.get(name), "std_msgs/msg/Float64")
        self.publish(f"/orccad/output/{name}", msgtype, _message(msgtype, value), time_ns)

    def commands(self) -> list[JointCommand]:
        """The joint commands received since the last call, in order."""
        return _drain(self._commands)

    def inputs(self) -> list[tuple[str, Any]]:
        """The mission inputs received since the last call: ``(name, value)``."""
        return _drain(self._inputs)

    def close(self) -> None:
        """Undeclare everything and close the session (idempotent)."""
        if self._closed:
            return
        self._closed = True
        for token in self._tokens:
            token.undeclare()
        self._session.close()


def _joint_actuators(model: Any) -> dict[str, int]:
    """Joint name -> the index of the actuator that drives it (a joint transmission)."""
    import mujoco

    found = {}
    for actuator in range(model.nu):
        if int(model.actuator_trntype[actuator]) == int(mujoco.mjtTrn.mjTRN_JOINT):
            joint = int(model.actuator_trnid[actuator, 0])
            found[model.joint(joint).name or f"joint{joint}"] = actuator
    return found


def _drain(found: queue.Queue) -> list:
    items = []
    while True:
        try:
            items.append(found.get_nowait())
        except queue.Empty:
            return items


class MissionBridge(MissionObserver):
    """``orccad run --ros2-zenoh``: a :class:`ZenohBridge` on a mission run (see the module
    docstring); :attr:`applied` counts the joint commands written to the plant and
    :attr:`raised` the inputs raised."""

    def __init__(self, mission_run: Any, connect: list[str], *,
                 domain_id: int | None = None) -> None:
        from orccad_app.trace.scene import robot_scene
        from orccad_app.trace.writers import sensor_ports

        plan = mission_run.plan
        roles = plan.roles
        self._run = mission_run
        self.bridge = ZenohBridge(
            connect, {s.name: s.type for s in plan.automaton.inputs},
            {s.name: s.type for s in plan.automaton.outputs if roles.get(s.name) is None},
            domain_id)
        self._robots = {name: (plant, robot_scene(name, plant.model).joints)
                        for name, plant in mission_run.plants.items()}
        self._actuators = {name: _joint_actuators(plant.model)
                           for name, plant in mission_run.plants.items()}
        self._sensed = {key: sensor.split(".", 1)[0]
                        for key, sensor in sensor_ports(plan).items()}
        self._published_at: dict[str, int] = {}
        self._outputs_sent = 0
        self.applied = 0
        self.raised = 0

    def on_read(self, t_ns: int, module: str, port: str, value: Any) -> None:
        robot = self._sensed.get((module, port))
        if robot is None or self._published_at.get(robot) == t_ns:
            return
        self._published_at[robot] = t_ns
        plant, joints = self._robots[robot]
        data = plant.data
        if joints.names:
            self.bridge.joint_states(t_ns, joints.names, [float(data.qpos[i]) for i in joints.qpos],
                                     [float(data.qvel[i]) for i in joints.dof],
                                     [float(data.qfrc_actuator[i]) for i in joints.dof])

    def on_reaction(self, t_ns: int, inputs: tuple[str, ...], outputs: tuple[str, ...],
                    status: str) -> None:
        self._publish_outputs()
        self.bridge.reached()  # a router started after the run is noticed
        for name, value in self.bridge.inputs():
            self._run.inject(name, value)
            self.raised += 1
        for command in self.bridge.commands():
            self._apply(command)

    def _publish_outputs(self) -> None:
        emitted = self._run.outputs
        for time_ns, name, value in emitted[self._outputs_sent:]:
            self.bridge.output(time_ns, name, value)
        self._outputs_sent = len(emitted)

    def _apply(self, command: JointCommand) -> None:
        """Each effort on the actuator of its joint (a joint without one: ignored)."""
        for robot, (plant, _) in self._robots.items():
            actuators = self._actuators[robot]
            named = [name for name in command.effort if name in actuators]
            if not named:
                continue
            tau = np.array(plant.ctrl, dtype=float)
            for name in named:
                tau[actuators[name]] = command.effort[name]
            plant.actuate("tau", tau)
            self.applied += 1

    def close(self) -> None:
        """Publish the outputs of the last reaction, then close the session."""
        try:
            self._publish_outputs()
            time.sleep(0.2)  # let the last messages leave before the session closes
        finally:
            self.bridge.close()
