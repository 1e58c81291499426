"""MCAP traces Foxglove plots out of the box (issue 18): one topic per port or plant signal
with a stable numeric schema, the event log as ``foxglove.Log``, no NaN, every message valid
against its channel's JSON Schema."""

from __future__ import annotations

import json
import math
from collections import defaultdict

import jsonschema
import pytest
from mcap.reader import make_reader

from orccad_app.trace import McapTraceWriter, TraceRow


def _strict(text: bytes):
    def refuse(constant):
        raise ValueError(f"non-strict JSON constant {constant}")
    return json.loads(text, parse_constant=refuse)


@pytest.fixture(scope="module")
def trace(recovery_run):
    with open(recovery_run.path, "rb") as stream:
        reader = make_reader(stream)
        summary = reader.get_summary()
        messages = defaultdict(list)
        for schema, channel, message in reader.iter_messages():
            messages[channel.topic].append((schema, channel, message))
    return summary, messages


def test_every_message_parses_with_its_channel_schema(trace):
    summary, messages = trace
    assert len(summary.channels) > 30
    for topic, items in messages.items():
        schema, channel, _ = items[0]
        assert (channel.message_encoding, schema.encoding) == ("json", "jsonschema"), topic
        validator = jsonschema.Draft202012Validator(json.loads(schema.data))
        for item_schema, _item_channel, message in items:
            assert item_schema.id == schema.id  # one schema per topic
            validator.validate(_strict(message.data))


def test_port_and_plant_topics_are_numeric_with_a_fixed_shape(trace):
    _, messages = trace
    ports = {t: m for t, m in messages.items() if t.startswith(("/ports/", "/plant/"))}
    assert {"/plant/arm/q", "/plant/arm/qdot", "/ports/TrackPID/ctrl/tau",
            "/ports/Park/ctrl/e", "/ports/TrackPID/tracking_error/value",
            "/ports/TrackPID/ctrl/saturated"} <= set(ports)
    for topic, items in ports.items():
        schema = json.loads(items[0][0].data)["properties"]["value"]
        values = [_strict(m.data)["value"] for _, _, m in items]
        if schema["type"] == "array":
            assert schema["items"] == {"type": "number"}
            assert {len(v) for v in values} == {schema["minItems"]} == {schema["maxItems"]}
            assert all(math.isfinite(x) for v in values for x in v), topic
        else:
            assert schema["type"] == "number", topic
            assert all(isinstance(v, (int, float)) and not isinstance(v, bool)
                       and math.isfinite(v) for v in values), topic
    q = [_strict(m.data)["value"] for _, _, m in messages["/plant/arm/q"]]
    assert len(q[0]) == 3
    times = [m.log_time for _, _, m in messages["/plant/arm/q"]]
    assert times == sorted(set(times))  # once per instant


def test_the_story_is_a_foxglove_log_and_tasks_are_markers(trace):
    _, messages = trace
    schema = json.loads(messages["/log"][0][0].data)
    assert messages["/log"][0][0].name == "foxglove.Log"
    assert schema["required"] == ["timestamp", "level", "message", "name", "file", "line"]
    log = [(m.log_time, _strict(m.data)) for _, _, m in messages["/log"]]
    texts = [entry["message"] for _, entry in log]
    for text in ("Home starts (site 0)", "Home ends: good_end", "TrackPID starts (site 2)",
                 "input Stop", "Park starts (site 1)", "TrackPID ends: killed",
                 "output Started", "output Beat"):
        assert text in texts, text
    assert texts.count("output Beat") == 1 and texts.count("input Home.at_rest") == 1
    stop_ns, stop = next((t, e) for t, e in log if e["message"] == "input Stop")
    assert stop_ns == 3_000_000_000 and stop["timestamp"] == {"sec": 3, "nsec": 0}
    assert stop["level"] == 2 and stop["name"] == "mission"
    assert stop["file"].endswith("arm_recovery.orc")
    park = [(m.log_time, _strict(m.data)["value"])
            for _, _, m in messages["/mission/active/Park"]]
    assert park == [(3_000_000_000, 1)]  # still parking at --until 4
    events = [_strict(m.data) for _, _, m in messages["/mission/task"]]
    assert [(e["task"], e["event"], e["outcome"]) for e in events] == [
        ("Home", "start", ""), ("Home", "end", "good_end"), ("TrackPID", "start", ""),
        ("Park", "start", ""), ("TrackPID", "end", "killed")]


def test_a_nan_or_a_type_change_is_left_out_and_logged(tmp_path):
    path = tmp_path / "nan.mcap"
    writer = McapTraceWriter(path, {"file": "x.orc"})
    rows = [(1, "[1.0,2.0]"), (2, "[NaN,2.0]"), (3, "[1.0]"), (4, "[3.0,4.0]"), (5, "Infinity")]
    for t, value in rows:
        writer.write(TraceRow(t, "write", "T.m", "y", -1, value))
    writer.write(TraceRow(6, "write", "T.m", "z", -1, "NaN"))
    writer.write(TraceRow(7, "write", "T.m", "z", -1, "true"))
    writer.close()
    with open(path, "rb") as stream:
        found = defaultdict(list)
        for _, channel, message in make_reader(stream).iter_messages():
            found[channel.topic].append((message.log_time, _strict(message.data)))
    assert found["/ports/T/m/y"] == [(1, {"value": [1.0, 2.0]}), (4, {"value": [3.0, 4.0]})]
    assert found["/ports/T/m/z"] == [(7, {"value": 1})]
    warnings = [entry["message"] for _, entry in found["/log"] if entry["level"] == 3]
    assert warnings[0] == "T.m.y = [NaN, 2.0]: not finite or not a vector2, left out of /ports/T/m/y"
    assert warnings[1].startswith("T.m.z = NaN: not finite, left out of /ports/T/m/z")
    assert warnings[-1] == "values left out: /ports/T/m/y 3"
