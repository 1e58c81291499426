"""MCAP traces that Foxglove plots out of the box.

Every topic has one JSON Schema whose field types never change, and no message holds NaN or
an infinity (strict JSON). Topics (message encoding ``json``, schema encoding ``jsonschema``,
``log_time`` = ``publish_time`` = the simulated instant [ns]):

- ``/ports/<module>/<port>`` — each value a Module-Task **writes** (``/ports/TrackPID/ctrl/tau``,
  Foxglove path ``/ports/TrackPID/ctrl/tau.value[0]``): ``{"value": …}`` typed by the port's
  first value: ``number``, an ``array`` of ``number`` of fixed length (a vector port), or
  ``string``; booleans and events are ``number`` 0/1 (a plottable step).
- ``/plant/<robot>/<sensor>`` — the robot's sensors as the modules read them (noise included),
  once per instant (``/plant/arm/q.value[1]``), same typing.
- ``/mission/active/<Task>`` — ``{"value": 0|1}`` when a Robot-Task starts or ends: a step to
  plot next to the signals, marking the task's span.
- ``/mission/task`` — ``{"task", "site", "event": "start"|"end", "outcome"}`` (a State
  Transitions panel on ``/mission/task.task``).
- ``/mission/args/<Task>/<param>`` — ``{"value": …}`` at each start of the Robot-Task: the
  actual value of its parameter (``/mission/args/GoTo/target.value[0]``), typed like a port;
  ``/orccad/task_start`` also holds all of them as JSON text (``args_json``).
- ``/log`` — ``foxglove.Log``: the mission's story (task starts and ends, exceptions, inputs,
  new outputs, parameter changes, deadline misses, deadlocks, the final status) for the Log
  panel; ``name`` is ``mission``, ``executive`` or ``trace``.
- ``/orccad/<event>`` — every other executive event of :mod:`orccad_app.trace.recorder` with
  its own flat schema (``/orccad/finish``: ``module``, ``job``, ``response_ns``, ``missed``),
  and ``/orccad/read`` (every read: ``module``, ``port``, ``value_json``), so the file holds
  the whole run like the CSV.

**Non-finite values and type changes.** A port value that is not finite (NaN, ±inf), or
whose type or length differs from the topic's first value, is left out of its ``/ports`` or
``/plant`` topic and reported once per topic as a ``WARNING`` on ``/log`` (its text keeps the
value); the total per topic is in the final ``trace`` log entry. Foxglove cannot plot a NaN and
a JSON parser refuses it: a gap in the plot and a warning say what happened.

A metadata record ``orccad`` holds the run's description (mission, seed, file). Chunks are
zstd-compressed; the output is deterministic (same rows → same bytes).

:class:`TopicWriter` maps rows to these topics and messages; :class:`McapTraceWriter` writes
them to the file, and :class:`~orccad_app.trace.foxglove_live.FoxgloveLiveWriter` streams the
same topics to Foxglove over its WebSocket protocol (``orccad run --foxglove``).
"""

from __future__ import annotations

import json
import math
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import IO, TYPE_CHECKING, Any

from orccad_app.mission.result import TaskOutcome
from orccad_app.reactive.status import Status
from orccad_app.trace.recorder import TraceRow
from orccad_app.trace.state_topics import (PHASE_SCHEMA, STATE_SCHEMA, VERDICT_SCHEMA,
                                           VerdictSample, phase_message, state_message,
                                           verdict_message)

if TYPE_CHECKING:  # the scene needs MuJoCo: imported when a run's robot is traced
    from orccad_app.trace.scene import RobotScene, Transform
    from orccad_app.robottask.signals import SignalRoles

__all__ = ["TopicWriter", "McapTraceWriter", "LOG_SCHEMA", "EVENT_FIELDS", "port_schema"]

_STRING = {"type": "string"}
_INTEGER = {"type": "integer"}
_NUMBER = {"type": "number"}
_BOOLEAN = {"type": "boolean"}
_STRINGS = {"type": "array", "items": _STRING}

LOG_SCHEMA = {
    "title": "foxglove.Log", "description": "A log message", "type": "object",
    "properties": {
        "timestamp": {"type": "object", "title": "time",
                      "properties": {"sec": {"type": "integer", "minimum": 0},
                                     "nsec": {"type": "integer", "minimum": 0,
                                              "maximum": 999_999_999}}},
        "level": {"title": "foxglove.LogLevel",
                  "oneOf": [{"title": title, "const": value} for value, title in
                            enumerate(("UNKNOWN", "DEBUG", "INFO", "WARNING", "ERROR",
                                       "FATAL"))]},
        "message": _STRING, "name": _STRING, "file": _STRING,
        "line": {"type": "integer", "minimum": 0}},
    "required": ["timestamp", "level", "message", "name", "file", "line"],
}
"""Foxglove's ``foxglove.Log`` (its core fields), as a JSON Schema."""

INFO, WARNING, ERROR = 2, 3, 4

_MODULE_JOB = (("module", _STRING), ("job", _INTEGER))
_ON_PROCESSOR = _MODULE_JOB + (("processor", _STRING),)

EVENT_FIELDS: dict[str, tuple[tuple[str, dict], ...]] = {
    "release": _MODULE_JOB,
    "start": _ON_PROCESSOR, "preempt": _ON_PROCESSOR, "resume": _ON_PROCESSOR,
    "compute_end": _ON_PROCESSOR,
    "finish": _MODULE_JOB + (("response_ns", _INTEGER), ("missed", _BOOLEAN)),
    "overrun": (("module", _STRING), ("unfinished_job", _INTEGER)),
    "block": (("module", _STRING), ("port", _STRING), ("op", _STRING), ("protocol", _STRING)),
    "unblock": (("module", _STRING), ("port", _STRING), ("op", _STRING),
                ("blocked_ns", _INTEGER)),
    "read": (("module", _STRING), ("port", _STRING), ("value_json", _STRING)),
    "signal": (("name", _STRING), ("value_json", _STRING)),
    "message": (("bus", _STRING), ("connection", _STRING), ("kind", _STRING),
                ("queued_ns", _INTEGER)),
    "activate": (("module", _STRING),), "kill": (("module", _STRING),),
    "param": (("module", _STRING), ("param", _STRING), ("value_json", _STRING)),
    "deadlock": (("cycle", _STRINGS),),
    "reaction": (("inputs", _STRINGS), ("outputs", _STRINGS), ("status", _STRING)),
    "task_start": (("task", _STRING), ("site", _INTEGER), ("args_json", _STRING)),
    "task_end": (("task", _STRING), ("site", _INTEGER), ("outcome", _STRING)),
    "exception": (("task", _STRING), ("name", _STRING), ("type", _INTEGER)),
    "update": (("module", _STRING), ("param", _STRING), ("exception", _STRING),
               ("update_json", _STRING)),
}
"""The flat fields of each ``/orccad/<event>`` topic, with their JSON types."""


def _get(value: Any, key: str, default: Any) -> Any:
    return value.get(key, default) if isinstance(value, dict) else default


def _event_message(event: str, module: str, port: str, job: int, value: Any,
                   text: str) -> dict[str, Any]:
    """The flat message of one row on ``/orccad/<event>`` (see :data:`EVENT_FIELDS`)."""
    if event in ("release",):
        return {"module": module, "job": job}
    if event in ("start", "preempt", "resume", "compute_end"):
        return {"module": module, "job": job, "processor": str(value or "")}
    if event == "finish":
        return {"module": module, "job": job, "response_ns": int(_get(value, "response_ns", 0)),
                "missed": bool(_get(value, "missed", False))}
    if event == "overrun":
        return {"module": module, "unfinished_job": int(value if value is not None else -1)}
    if event == "block":
        return {"module": module, "port": port, "op": str(_get(value, "op", "")),
                "protocol": str(_get(value, "protocol", ""))}
    if event == "unblock":
        return {"module": module, "port": port, "op": str(_get(value, "op", "")),
                "blocked_ns": int(_get(value, "blocked_ns", 0))}
    if event == "message":
        return {"bus": module, "connection": port, "kind": str(_get(value, "kind", "")),
                "queued_ns": int(_get(value, "queued_ns", 0))}
    if event in ("activate", "kill"):
        return {"module": module}
    if event == "read":
        return {"module": module, "port": port, "value_json": text}
    if event == "signal":
        return {"name": port, "value_json": text}
    if event == "param":
        return {"module": module, "param": port, "value_json": text}
    if event == "deadlock":
        return {"cycle": [str(item) for item in value or []]}
    if event == "reaction":
        return {"inputs": list(_get(value, "inputs", [])), "outputs": list(_get(value, "outputs",
                                                                                 [])),
                "status": str(_get(value, "status", ""))}
    if event == "task_start":
        return {"task": module, "site": job, "args_json": text or "{}"}
    if event == "task_end":
        return {"task": module, "site": job, "outcome": str(value or "")}
    if event == "exception":
        return {"task": module, "name": port, "type": int(value or 0)}
    if event == "update":
        return {"module": module, "param": port, "exception": str(_get(value, "exception", "")),
                "update_json": text}
    raise ValueError(f"unknown trace event {event!r}")


def _object_schema(title: str, fields: tuple[tuple[str, dict], ...]) -> dict[str, Any]:
    return {"title": title, "type": "object", "properties": dict(fields),
            "required": [name for name, _ in fields]}


def port_schema(value: Any) -> tuple[dict[str, Any], str] | None:
    """The ``value`` field's JSON Schema for a port whose first value is ``value``, and a key
    that later values must match; ``None`` when the value cannot start a topic (not finite)."""
    if isinstance(value, bool):
        return _NUMBER, "number"
    if isinstance(value, (int, float)):
        return (_NUMBER, "number") if math.isfinite(value) else None
    if isinstance(value, list) and value and all(
            isinstance(v, (int, float)) and not isinstance(v, bool) for v in value):
        if not all(math.isfinite(v) for v in value):
            return None
        n = len(value)
        return ({"type": "array", "items": _NUMBER, "minItems": n, "maxItems": n},
                f"vector{n}")
    return _STRING, "string"


def _plain(value: Any, key: str) -> Any | None:
    """``value`` as the topic typed ``key`` holds it, or ``None`` if it does not fit."""
    if key == "number":
        if isinstance(value, bool):
            return 1 if value else 0
        if isinstance(value, (int, float)) and math.isfinite(value):
            return value
        return None
    if key == "string":
        return value if isinstance(value, str) else json.dumps(value, allow_nan=True)
    if (isinstance(value, list) and f"vector{len(value)}" == key
            and all(isinstance(v, (int, float)) and not isinstance(v, bool)
                    and math.isfinite(v) for v in value)):
        return value
    return None


class _Topic:
    __slots__ = ("channel", "key", "dropped")

    def __init__(self, channel: Any, key: str) -> None:
        self.channel, self.key, self.dropped = channel, key, 0


class TopicWriter:
    """Rows to the Foxglove topics of the module docstring; a subclass says where the
    messages go (:meth:`_register` a topic, :meth:`_publish` a message, :meth:`_finish`).

    :param sensors: ``(module, input port)`` fed by a robot sensor -> the sensor
        (``("TrackPID.ctrl", "q") -> "arm.q"``), for the ``/plant`` topics.
    """

    def __init__(self, metadata: Mapping[str, str] | None = None,
                 sensors: Mapping[tuple[str, str], str] | None = None) -> None:
        self._sensors = dict(sensors or {})
        self._file_name = str((metadata or {}).get("file", ""))
        self._channels: dict[str, Any] = {}
        self._topics: dict[str, _Topic] = {}
        self._sensed: dict[str, int] = {}  # plant topic -> last instant written
        self._present: set[str] = set()
        self._inputs: set[str] = set()
        self._status: str = Status.RUNNING
        self._sequence = 0
        self._last_ns = 0
        self._closed = False
        self._tf_dropped = False
        self._roles: SignalRoles | None = None
        self._log_channel = self._channel("/log", "foxglove.Log", LOG_SCHEMA)

    def signal_roles(self, roles: SignalRoles) -> None:
        """The roles of the mission's generated signals: ``/log`` says an observer event once
        while it holds and leaves generated outputs (``X.start``…) out. (Without them every
        signal is taken for one of the mission's own.)"""
        self._roles = roles

    def _is_own(self, signal: str) -> bool:
        return self._roles is None or self._roles.is_own(signal)

    # -- the sink ---------------------------------------------------------------------------

    def _register(self, topic: str, name: str, schema: str, latched: bool) -> Any:
        """A channel for ``topic`` whose messages follow the JSON Schema ``schema`` (text)
        called ``name``; ``latched``: a state topic, whose last message a live sink sends again
        to a client that subscribes late."""
        raise NotImplementedError

    def _publish(self, channel: Any, time_ns: int, body: bytes, sequence: int) -> None:
        """Send one JSON message on ``channel`` at simulated instant ``time_ns``."""
        raise NotImplementedError

    def _finish(self) -> None:
        """The last message was sent."""

    # -- channels ---------------------------------------------------------------------------

    def _channel(self, topic: str, name: str, schema: dict[str, Any],
                 latched: bool = False) -> Any:
        channel = self._channels.get(topic)
        if channel is None:
            channel = self._register(topic, name, json.dumps(schema, sort_keys=True), latched)
            self._channels[topic] = channel
        return channel

    def _emit(self, channel: Any, time_ns: int, message: dict[str, Any]) -> None:
        self._sequence += 1
        self._last_ns = max(self._last_ns, time_ns)
        body = json.dumps(message, separators=(",", ":"), allow_nan=False)
        self._publish(channel, time_ns, body.encode(), self._sequence)

    def log(self, time_ns: int, level: int, name: str, message: str, line: int = 0) -> None:
        """A ``foxglove.Log`` entry on ``/log``."""
        self._emit(self._log_channel, time_ns, {
            "timestamp": {"sec": time_ns // 1_000_000_000, "nsec": time_ns % 1_000_000_000},
            "level": level, "message": message, "name": name, "file": self._file_name,
            "line": line})

    # -- rows -------------------------------------------------------------------------------

    def write(self, row: TraceRow) -> None:
        """Append one row: its ``/orccad`` event or port topic, plant topic and log entry."""
        time_ns, event, module, port, job, text = row
        value = json.loads(text) if text else None
        if event == "write":
            self._sample(time_ns, f"/ports/{module.replace('.', '/')}/{port}",
                         f"{module}.{port}", value)
            return
        if event == "param":
            self.param(time_ns, module, port, value)
        if event == "read":
            sensor = self._sensors.get((module, port))
            if sensor is not None:
                topic = f"/plant/{sensor.replace('.', '/')}"
                if self._sensed.get(topic) != time_ns:
                    self._sensed[topic] = time_ns
                    self._sample(time_ns, topic, sensor, value)
        fields = EVENT_FIELDS[event]
        message = _event_message(event, module, port, job, value, text)
        self._emit(self._channel(f"/orccad/{event}", f"orccad.{event}",
                                 _object_schema(f"orccad.{event}", fields)), time_ns, message)
        self._story(time_ns, event, message)

    # -- the run's state and the robot (:mod:`.run_topics` calls these) ---------------------

    def scene(self, time_ns: int, scenes: list[RobotScene]) -> None:
        """The robots' geometry on ``/scene`` (``foxglove.SceneUpdate``, a state topic)."""
        from orccad_app.trace.scene import SCENE_UPDATE_SCHEMA, scene_message

        self._emit(self._channel("/scene", "foxglove.SceneUpdate", SCENE_UPDATE_SCHEMA,
                                 latched=True), time_ns, scene_message(time_ns, scenes))

    def transforms(self, time_ns: int, transforms: list[Transform]) -> None:
        """The bodies' frames at ``time_ns`` on ``/tf`` (``foxglove.FrameTransforms``, a state
        topic); a transform that is not finite (a diverged plant) is left out, with a warning
        once."""
        from orccad_app.trace.scene import FRAME_TRANSFORMS_SCHEMA, transforms_message

        finite = [t for t in transforms if all(math.isfinite(v) for v in
                                               (*t.translation, *t.rotation))]
        if len(finite) < len(transforms) and not self._tf_dropped:
            self._tf_dropped = True
            self.log(time_ns, WARNING, "trace", "a body's pose is not finite: left out of /tf")
        if finite:
            self._emit(self._channel("/tf", "foxglove.FrameTransforms", FRAME_TRANSFORMS_SCHEMA,
                                     latched=True), time_ns,
                       transforms_message(time_ns, finite))

    wants_joint_states = False
    """Whether :meth:`joint_state` records anything (a rosbag2 trace); the Foxglove topics
    hold the robot's sensors on ``/plant`` and its frames on ``/tf`` instead."""

    def joint_state(self, time_ns: int, robot: str, names: tuple[str, ...],
                    position: list[float], velocity: list[float],
                    effort: list[float]) -> None:
        """The state of ``robot``'s joints at ``time_ns`` [rad, rad/s, N·m] (or [m, m/s, N]
        for a slide joint): ignored here."""

    def pose(self, time_ns: int, robot: str, transform: Transform) -> None:
        """The pose of ``robot``'s floating base in ``world``: on ``/tf`` here already."""

    def mission_state(self, time_ns: int, state: int, waiting_at: list[Any],
                      status: str) -> None:
        """The automaton's new state on ``/mission/state`` (:mod:`.state_topics`)."""
        self._emit(self._channel("/mission/state", "orccad.AutomatonState", STATE_SCHEMA,
                                 latched=True), time_ns,
                   state_message(state, waiting_at, status))

    def phase(self, time_ns: int, task: str, phase: int) -> None:
        """Robot-Task ``task``'s new phase on ``/mission/phase/<task>``."""
        self._emit(self._channel(f"/mission/phase/{task}", "orccad.Phase", PHASE_SCHEMA,
                                 latched=True), time_ns, phase_message(phase))

    def verdict(self, time_ns: int, sample: VerdictSample) -> None:
        """A property's verdict so far on ``/properties/<name>``."""
        self._emit(self._channel(f"/properties/{sample.name}", "orccad.Verdict",
                                 VERDICT_SCHEMA, latched=True), time_ns,
                   verdict_message(sample))

    def param(self, time_ns: int, module: str, param: str, value: Any) -> None:
        """The value of ``module``'s parameter ``param`` from ``time_ns`` on (its nominal
        value when its Robot-Task starts, each type-1 update) on ``/params/<module>/<param>``,
        typed like a port (``/params/TrackPID/ctrl/kp.value``); a state topic."""
        self._sample(time_ns, f"/params/{module.replace('.', '/')}/{param}",
                     f"{module}.{param}", value, latched=True)

    def _sample(self, time_ns: int, topic: str, what: str, value: Any,
                latched: bool = False) -> None:
        state = self._topics.get(topic)
        if state is None:
            typed = port_schema(value)
            if typed is None:
                self.log(time_ns, WARNING, "trace", f"{what} = {json.dumps(value)}: not finite, "
                         f"left out of {topic} (its topic starts at the first finite value)")
                return
            schema, key = typed
            channel = self._channel(topic, "orccad.PortValue",
                                    _object_schema("orccad.PortValue", (("value", schema),)),
                                    latched)
            state = self._topics[topic] = _Topic(channel, key)
        plain = _plain(value, state.key)
        if plain is None:
            if not state.dropped:
                self.log(time_ns, WARNING, "trace", f"{what} = {json.dumps(value)}: not finite "
                         f"or not a {state.key}, left out of {topic}")
            state.dropped += 1
            return
        self._emit(state.channel, time_ns, {"value": plain})

    def _story(self, time_ns: int, event: str, m: dict[str, Any]) -> None:
        """The mission's events on ``/log`` and the task markers."""
        if event == "task_start":
            self._active(time_ns, m["task"], 1, m["site"], "start", "")
            self.log(time_ns, INFO, "mission", f"{m['task']} starts (site {m['site']})")
            for param, value in json.loads(m["args_json"]).items():
                self._sample(time_ns, f"/mission/args/{m['task']}/{param}",
                             f"{m['task']}.{param}", value, latched=True)
        elif event == "task_end":
            self._active(time_ns, m["task"], 0, m["site"], "end", m["outcome"])
            level = INFO if m["outcome"] == TaskOutcome.GOOD_END else WARNING
            self.log(time_ns, level, "mission", f"{m['task']} ends: {m['outcome']}")
        elif event == "exception":
            level = {1: INFO, 2: WARNING}.get(m["type"], ERROR)
            origin = f" from {m['task']}" if m["task"] else ""
            self.log(time_ns, level, "mission", f"exception {m['name']} (type {m['type']})"
                                                f"{origin}")
        elif event == "reaction":
            self._reaction(time_ns, m)
        elif event == "param":
            self.log(time_ns, INFO, "executive", f"{m['module']}.{m['param']} := "
                                                 f"{m['value_json']}")
        elif event == "update":
            change = json.loads(m["update_json"])
            ramp = change.get("ramp")
            new = (f"ramp {ramp['start']} -> {ramp['end']} over {ramp['duration_s']} s"
                   if ramp else f"{change.get('new')}")
            self.log(time_ns, INFO, "mission", f"type-1 update by {m['exception']}: "
                                               f"{m['module']}.{m['param']} {change.get('old')} "
                                               f"-> {new}")
        elif event == "finish" and m["missed"]:
            self.log(time_ns, WARNING, "executive", f"{m['module']} job {m['job']} finished "
                                                    "after its deadline")
        elif event == "overrun":
            self.log(time_ns, WARNING, "executive", f"{m['module']}: release skipped (job "
                                                    f"{m['unfinished_job']} unfinished)")
        elif event == "deadlock":
            self.log(time_ns, ERROR, "executive", "deadlock: " + " -> ".join(m["cycle"]))

    def _active(self, time_ns: int, task: str, value: int, site: int, what: str,
                outcome: str) -> None:
        topic = f"/mission/active/{task}"
        schema = _object_schema("orccad.Active", (("value", _INTEGER),))
        self._emit(self._channel(topic, "orccad.Active", schema, latched=True), time_ns,
                   {"value": value})
        fields = (("task", _STRING), ("site", _INTEGER), ("event", _STRING), ("outcome", _STRING))
        self._emit(self._channel("/mission/task", "orccad.TaskEvent",
                                 _object_schema("orccad.TaskEvent", fields)), time_ns,
                   {"task": task, "site": site, "event": what, "outcome": outcome})

    def _reaction(self, time_ns: int, m: dict[str, Any]) -> None:
        inputs = set(m["inputs"])
        own = self._is_own
        for name in sorted(inputs):  # an observer event (X.E) while it holds: once
            if own(name) or name not in self._inputs:
                self.log(time_ns, INFO, "mission", f"input {name}")
        self._inputs = inputs
        outputs = {name for name in m["outputs"] if own(name)}
        for name in sorted(outputs - self._present):  # a sustained output once
            self.log(time_ns, INFO, "mission", f"output {name}")
        self._present = outputs
        status = m["status"]
        if status != self._status and status in (Status.DONE, Status.FAILED, Status.ABORTED):
            self.log(time_ns, INFO if status == Status.DONE else ERROR, "mission",
                     f"mission {status}")
        self._status = status

    def close(self) -> None:
        """Say what was left out, then finish (idempotent)."""
        if self._closed:
            return
        self._closed = True
        try:
            dropped = {t: s.dropped for t, s in self._topics.items() if s.dropped}
            if dropped:
                self.log(self._last_ns, WARNING, "trace", "values left out: " + ", ".join(
                    f"{topic} {count}" for topic, count in sorted(dropped.items())))
        finally:
            self._finish()


class McapTraceWriter(TopicWriter):
    """Rows to an MCAP file Foxglove plots (see the module docstring).

    :param sensors: ``(module, input port)`` fed by a robot sensor -> the sensor
        (``("TrackPID.ctrl", "q") -> "arm.q"``), for the ``/plant`` topics.
    """

    def __init__(self, path: str | Path, metadata: Mapping[str, str] | None = None,
                 sensors: Mapping[tuple[str, str], str] | None = None,
                 opener: Callable[..., IO[bytes]] = open) -> None:
        from mcap.writer import Writer

        self.path = str(path)
        self._file: IO[bytes] = opener(path, "wb")
        self._writer = Writer(self._file)
        self._writer.start(profile="", library="orccad")
        self._schemas: dict[str, int] = {}
        if metadata:
            self._writer.add_metadata("orccad", {k: str(v) for k, v in metadata.items()})
        super().__init__(metadata, sensors)

    def _register(self, topic: str, name: str, schema: str, latched: bool) -> int:
        schema_id = self._schemas.get(schema)
        if schema_id is None:
            schema_id = self._writer.register_schema(name, "jsonschema", schema.encode())
            self._schemas[schema] = schema_id
        return self._writer.register_channel(topic, "json", schema_id)

    def _publish(self, channel: int, time_ns: int, body: bytes, sequence: int) -> None:
        self._writer.add_message(channel, time_ns, body, time_ns, sequence)

    def _finish(self) -> None:
        try:
            self._writer.finish()
        finally:
            self._file.close()
