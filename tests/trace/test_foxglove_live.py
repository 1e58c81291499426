"""``orccad run --foxglove``: a live run streamed to Foxglove over its WebSocket protocol, with
the MCAP trace's topics and schemas (issue 18). A WebSocket client (``websockets``) speaks the
protocol as the Foxglove app does: it subscribes to every channel advertised and decodes the
binary message frames (opcode 1, subscription id, log time, JSON payload)."""

from __future__ import annotations

import json
import socket
import struct
import subprocess
import sys
import time

import jsonschema
import pytest
from mcap.reader import make_reader

# TrackPID runs 1 s (250 ms of wall time at --realtime 4) before Stop parks the arm: time for
# a client to subscribe to its ports' channels, advertised when their first value comes
ROOT_ARGS = [sys.executable, "-m", "orccad_app.cli", "run", "missions/arm_recovery.orc",
             "--inject", "Stop@2.5", "--until", "5"]


def test_without_the_extra_the_run_says_what_to_install():
    blocked = ("import sys; sys.modules['foxglove'] = None; from orccad_app.cli import main; "
               "sys.exit(main(['run', 'missions/arm_pid.orc', '--foxglove']))")
    result = subprocess.run([sys.executable, "-c", blocked], capture_output=True, text=True,
                            timeout=120)
    assert result.returncode == 2, result.stderr
    assert "pip install -e '.[foxglove]'" in result.stderr and "foxglove-sdk" in result.stderr
    assert "Traceback" not in result.stderr and result.stdout == ""


def _free_port() -> int:
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]


def _connect(port: int, process: subprocess.Popen):
    from websockets.sync.client import connect

    start = time.monotonic()
    while time.monotonic() - start < 90:
        assert process.poll() is None, process.communicate()[1]
        try:
            return connect(f"ws://127.0.0.1:{port}", open_timeout=2,
                           subprotocols=["foxglove.sdk.v1", "foxglove.websocket.v1"])
        except OSError:
            time.sleep(0.1)
    raise AssertionError("the Foxglove server did not come up")


def _listen(ws) -> tuple[dict, dict]:
    """Subscribe to every channel advertised; the channels by topic and the messages received
    on each, until the server closes at the end of the run."""
    from websockets.exceptions import ConnectionClosed

    channels, by_subscription, received = {}, {}, {}
    while True:
        try:
            frame = ws.recv(timeout=60)
        except ConnectionClosed:
            return channels, received
        if isinstance(frame, str):
            message = json.loads(frame)
            if message["op"] == "advertise":
                subscriptions = []
                for channel in message["channels"]:
                    channels[channel["topic"]] = channel
                    number = len(by_subscription) + 1
                    by_subscription[number] = channel["topic"]
                    subscriptions.append({"id": number, "channelId": channel["id"]})
                ws.send(json.dumps({"op": "subscribe", "subscriptions": subscriptions}))
        elif frame[0] == 1:  # a message: subscription id, log time [ns], payload
            number, log_time = struct.unpack_from("<IQ", frame, 1)
            topic = by_subscription[number]
            received.setdefault(topic, []).append((log_time, json.loads(frame[13:])))


def test_a_live_run_streams_the_trace_topics_to_a_websocket_client(tmp_path):
    pytest.importorskip("foxglove", reason="the foxglove extra is not installed")
    pytest.importorskip("websockets")
    port, mcap = _free_port(), tmp_path / "run.mcap"
    process = subprocess.Popen([*ROOT_ARGS, "--realtime", "4", "--trace", str(mcap),
                                "--foxglove", "--foxglove-port", str(port)],
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        with _connect(port, process) as ws:
            channels, received = _listen(ws)
        out, err = process.communicate(timeout=120)
    finally:
        process.kill()
    assert f"streaming to Foxglove on ws://127.0.0.1:{port}" in err
    assert process.returncode == 0, err
    # the run waited for the client: the story from the first instant on
    log = [m["message"] for _, m in received["/log"]]
    assert "Home starts (site 0)" in log[:3] and "input Stop" in log and "mission done" in log
    assert channels["/log"]["schemaName"] == "foxglove.Log"
    for topic in ("/plant/arm/q", "/ports/TrackPID/ctrl/tau", "/mission/active/Home",
                  "/mission/task"):
        assert received.get(topic), f"nothing on {topic}"
    q = received["/plant/arm/q"]
    assert all(len(m["value"]) == 3 for _, m in q) and q[0][0] < 500_000_000  # near 0 s
    with mcap.open("rb") as stream:  # the same run's MCAP trace: same topics and schemas
        reader = make_reader(stream)
        summary = reader.get_summary()
        traced = {c.topic: summary.schemas[c.schema_id] for c in summary.channels.values()}
    for topic, channel in channels.items():
        assert topic in traced, topic
        assert channel["schemaName"] == traced[topic].name
        schema = json.loads(channel["schema"])
        assert schema == json.loads(traced[topic].data)
        for _, message in received.get(topic, [])[:50]:
            jsonschema.validate(message, schema)


def test_a_client_that_subscribes_late_gets_the_current_state(tmp_path):
    """State topics are latched: a client that subscribes in the middle of a run (the run
    did not wait for it) gets at once the last message of each — the geometry sent before
    the run, Home's span and phase, the gain set when TrackPID started — so every span and
    value shows, not only the changes after it subscribed."""
    pytest.importorskip("foxglove", reason="the foxglove extra is not installed")
    pytest.importorskip("websockets")
    port = _free_port()
    process = subprocess.Popen([sys.executable, "-m", "orccad_app.cli", "run",
                                "missions/arm_recovery.orc", "--inject", "Stop@3", "--until",
                                "6", "--foxglove", "--foxglove-port", str(port),
                                "--foxglove-wait", "0"],
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        with _connect(port, process) as ws:
            channels, subscribed_at, received = _subscribe_after(ws, 2_000_000_000)
        process.communicate(timeout=120)
    finally:
        process.kill()
    assert subscribed_at >= 2_000_000_000
    first = {topic: items[0] for topic, items in received.items()}
    assert first["/scene"][0] == 0 and first["/scene"][1]["entities"]
    assert first["/mission/active/Home"] == (1_500_100_000, {"value": 0})
    assert first["/mission/phase/Home"] == (1_500_100_000, {"value": 0, "phase": "idle"})
    assert first["/params/TrackPID/ctrl/kp"] == (1_500_100_000, {"value": 600.0})
    assert first["/mission/state"][0] < subscribed_at
    assert first["/tf"][0] <= subscribed_at  # the arm where it is now, at once
    for topic in ("/scene", "/mission/state", "/tf"):
        jsonschema.validate(first[topic][1], json.loads(channels[topic]["schema"]))


def _subscribe_after(ws, time_ns: int) -> tuple[dict, int, dict]:
    """Wait for the server's clock to pass ``time_ns``, then subscribe to every channel;
    the channels, the clock at subscription and the messages received, until the end."""
    from websockets.exceptions import ConnectionClosed

    channels, by_subscription, received = {}, {}, {}
    clock, subscribed_at = 0, None
    while True:
        try:
            frame = ws.recv(timeout=60)
        except ConnectionClosed:
            return channels, subscribed_at, received
        if isinstance(frame, str):
            message = json.loads(frame)
            if message["op"] == "advertise":
                for channel in message["channels"]:
                    channels[channel["topic"]] = channel
        elif frame[0] == 2:  # the server's time
            clock = struct.unpack_from("<Q", frame, 1)[0]
        elif frame[0] == 1:
            number, log_time = struct.unpack_from("<IQ", frame, 1)
            received.setdefault(by_subscription[number], []).append(
                (log_time, json.loads(frame[13:])))
        if subscribed_at is None and clock >= time_ns:
            subscribed_at = clock
            subscriptions = []
            for topic, channel in channels.items():
                by_subscription[len(by_subscription) + 1] = topic
                subscriptions.append({"id": len(by_subscription), "channelId": channel["id"]})
            ws.send(json.dumps({"op": "subscribe", "subscriptions": subscriptions}))
