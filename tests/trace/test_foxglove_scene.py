"""The robot moving in Foxglove's 3D panel and the run's state as topics (issue 26): an MCAP
trace of ``missions/arm_recovery.orc`` read back with the ``mcap`` reader alone — frames of
the MJCF kinematic tree on ``/tf``, the geometry on ``/scene``, parameters, phases, the
automaton's state and the properties' running verdicts — every schema a valid JSON Schema and
every message valid against it."""

from __future__ import annotations

import json
import math
from collections import defaultdict

import jsonschema
import mujoco
import numpy as np
import pytest
from mcap.reader import make_reader

from orccad_app.trace.scene import robot_scene


def _strict(text: bytes):
    def refuse(constant):
        raise ValueError(f"non-strict JSON constant {constant}")
    return json.loads(text, parse_constant=refuse)


@pytest.fixture(scope="module")
def trace(recovery_run):
    schemas, messages = {}, defaultdict(list)
    with open(recovery_run.path, "rb") as stream:
        for schema, channel, message in make_reader(stream).iter_messages():
            schemas[channel.topic] = schema
            messages[channel.topic].append((message.log_time, _strict(message.data)))
    verdicts = {p["name"]: p["verdict"] for p in recovery_run.report["properties"]}
    return schemas, messages, verdicts


def test_every_schema_is_a_json_schema_and_every_message_follows_it(trace):
    schemas, messages, _ = trace
    for topic, schema in schemas.items():
        document = json.loads(schema.data)
        jsonschema.Draft202012Validator.check_schema(document)
        validator = jsonschema.Draft202012Validator(document)
        for _, message in messages[topic]:
            validator.validate(message)
    assert schemas["/tf"].name == "foxglove.FrameTransforms"
    assert schemas["/scene"].name == "foxglove.SceneUpdate"


def _parents(messages) -> dict[str, str]:
    parents: dict[str, str] = {}
    for _, message in messages["/tf"]:
        for transform in message["transforms"]:
            child, parent = transform["child_frame_id"], transform["parent_frame_id"]
            assert parents.setdefault(child, parent) == parent, f"{child}: two parents"
    return parents


def test_frames_form_one_tree_rooted_at_the_world_and_are_finite(trace):
    _, messages, _ = trace
    parents = _parents(messages)
    assert parents == {"arm/link1": "world", "arm/link2": "arm/link1",
                       "arm/link3": "arm/link2"}
    for frame in parents:  # every frame reaches the world, without a cycle
        seen = [frame]
        while seen[-1] != "world":
            seen.append(parents[seen[-1]])
            assert len(seen) <= len(parents) + 1, f"cycle through {seen}"
    for time_ns, message in messages["/tf"]:
        for transform in message["transforms"]:
            values = [*transform["translation"].values(), *transform["rotation"].values()]
            assert all(math.isfinite(v) for v in values), transform
            norm = math.sqrt(sum(v * v for v in transform["rotation"].values()))
            assert norm == pytest.approx(1.0, abs=1e-9)
            assert transform["timestamp"] == {"sec": time_ns // 10**9, "nsec": time_ns % 10**9}
    scene = messages["/scene"]
    assert [t for t, _ in scene] == [0]  # once, before the run
    entities = {e["id"]: e for e in scene[0][1]["entities"]}
    assert set(entities) == {"arm/floor", "arm/pedestal", "arm/waist", "arm/upper_arm",
                             "arm/forearm"}
    assert {e["frame_id"] for e in entities.values()} <= set(parents) | {"world"}
    forearm = entities["arm/forearm"]  # a capsule: a cylinder and two spheres
    assert forearm["frame_locked"] and forearm["frame_id"] == "arm/link3"
    assert len(forearm["cylinders"]) == 1 and len(forearm["spheres"]) == 2
    assert forearm["cylinders"][0]["size"]["z"] == pytest.approx(0.4)


def test_the_frames_follow_the_plant(trace):
    """The waist turns by q[0] about z, the shoulder and elbow by q[1], q[2] about y: every
    frame agrees with the plant's joint positions read last before its instant (the frames
    are stamped with the plant's own time, a write after the read: within 0.3 ms of motion),
    and the arm moves."""
    _, messages, _ = trace
    reads = [(t, m["value"]) for t, m in messages["/plant/arm/q"]]
    scene = robot_scene("arm", mujoco.MjModel.from_xml_path("robots/arm3dof.xml"))
    compared, index = 0, 0
    for time_ns, message in messages["/tf"]:
        while index + 1 < len(reads) and reads[index + 1][0] <= time_ns:
            index += 1
        read_ns, q = reads[index]
        if not 0 <= time_ns - read_ns <= 1_000_000:
            continue  # no read in the last millisecond (between two tasks)
        expected = scene.transforms(np.asarray(q))
        for transform, want in zip(message["transforms"], expected):
            assert transform["child_frame_id"] == want.child_id
            got = tuple(transform["rotation"][k] for k in "xyzw")
            assert got == pytest.approx(want.rotation, abs=2e-3), time_ns
            assert tuple(transform["translation"][k] for k in "xyz") == pytest.approx(
                want.translation, abs=1e-9)
        compared += 1
    assert compared > 150
    waist = [2 * math.atan2(m["transforms"][0]["rotation"]["z"],
                            m["transforms"][0]["rotation"]["w"]) for _, m in messages["/tf"]]
    assert max(waist) - min(waist) > 0.4  # homed to 1 rad, tracked, parked: it moves
    times = [t for t, _ in messages["/tf"]]
    assert times[-1] == 4_000_000_000 and len(times) > 150  # 50 Hz, and the last instant


def test_parameters_phases_state_and_verdicts_are_topics(trace):
    _, messages, reported = trace
    assert messages["/params/TrackPID/ctrl/kp"] == [(1_500_100_000, {"value": 600.0})]
    phases = {task: [(t, m["value"]) for t, m in messages[f"/mission/phase/{task}"]]
              for task in ("Home", "TrackPID", "Park")}
    assert phases["TrackPID"][0] == (0, 0) and (3_000_000_000, 0) in phases["TrackPID"]
    assert any(value == 3 for _, value in phases["TrackPID"])
    assert phases["Park"][-1] == (3_000_000_000, 3)  # still parking at --until 4
    states = messages["/mission/state"]
    assert states[0][0] == 0 and len(states) >= 4
    assert all(m["waiting_at"] and m["at"] == ", ".join(m["waiting_at"]) for _, m in states)
    assert any("arm_recovery.orc" in m["at"] for _, m in states)
    verdicts = {topic.removeprefix("/properties/"): items for topic, items in messages.items()
                if topic.startswith("/properties/")}
    assert set(verdicts) == {"home_before_tracking", "one_task_at_a_time", "retry_after_a_loss",
                             "fatal_reported", "park_completes", "parked_before_done",
                             "finished_once"}
    for name, items in verdicts.items():
        assert items[-1][0] == 4_000_000_000 and len(items) > 30, name
    # the last verdict is the report's (a timeout cuts the run: LTL3 says what the prefix
    # decides), and each verdict changes as the run goes
    assert {name: items[-1][1]["verdict"] for name, items in verdicts.items()} == reported
    assert reported["park_completes"] == "undecided"
    assert reported["home_before_tracking"] == "true"
    assert verdicts["home_before_tracking"][0][1]["verdict"] == "undecided"
