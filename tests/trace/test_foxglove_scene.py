"""The robot moving in Foxglove's 3D panel and the run's state as topics (issue 26): an MCAP
trace of ``missions/arm_recovery.orc`` read back with the ``mcap`` reader alone — frames of
the MJCF kinematic tree on ``/tf``, the geometry on ``/scene``, parameters, phases, the
automaton's state and the properties' running verdicts — every schema a valid JSON Schema and
every message valid against it."""

from __future__ import annotations

import json
import math
from pathlib import Path
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


def test_the_frames_go_on_while_no_module_reads_the_robot(tmp_path):
    """After its task, the arm is read by no module during an ``await`` (its idle behaviour
    alone acts on it): the frames still come every 20 ms, each stamped with its own instant,
    showing the arm as the plant has it then; and the run is the one without a trace."""
    from orccad_app.pipeline import load, select_mission
    from orccad_app.session import RunOptions, run_mission

    source = tmp_path / "gap.orc"
    text = Path("missions/arm_pid.orc").read_text(encoding="utf-8")
    text = text.replace("duration 4 s", "duration 0.3 s").replace(
        "    run TrackPID();", "    run TrackPID();\n    await 0.3 s;")
    source.write_text("\n".join(line for line in text.splitlines()
                                if not line.startswith("property")), encoding="utf-8")
    program = load(str(source))
    mission = select_mission(program, None)
    path = tmp_path / "gap.mcap"
    traced = run_mission(program, mission, RunOptions(trace=str(path))).result
    plain = run_mission(program, mission, RunOptions()).result
    assert traced.status == plain.status == "done" and traced.sim_time_ns == 600_000_000
    assert [r.as_dict() for r in traced.robot_tasks] == [r.as_dict() for r in plain.robot_tasks]
    assert traced.outputs == plain.outputs
    with open(path, "rb") as stream:
        times = [message.log_time for _, _, message in
                 make_reader(stream).iter_messages(topics=["/tf"])]
    waiting = [t for t in times if 300_000_000 < t < 600_000_000]
    assert len(waiting) >= 14  # 50 Hz during the await (it was one stale stamp, repeated)
    assert all(b - a <= 21_000_000 for a, b in zip(times, times[1:]))
    assert len(set(waiting)) == len(waiting)
