"""``orccad run --ros2-zenoh`` (issue 26, experimental): two processes on loopback — the run
and this test as a Zenoh peer listening on ``tcp/127.0.0.1:PORT`` (no multicast, no gossip,
no DDS) — speaking rmw_zenoh's key expressions, CDR payloads and attachments: the test reads
``/joint_states``, sends a joint command and the mission's ``Stop`` input, and sees the
mission's output ``Stopping``."""

from __future__ import annotations

import socket
import re
import subprocess
import sys
import threading
import time

import pytest

from orccad_app.ros2.keyexpr import attachment, dds_type, read_attachment, topic_key

JOINT_STATE_HASH = "RIHS01_a13ee3a330e346c9d87b5aa18d24e11690752bd33a0350f11c5882bc9179260e"


def test_key_expressions_and_attachments_are_rmw_zenoh_s():
    assert dds_type("sensor_msgs/msg/JointState") == "sensor_msgs::msg::dds_::JointState_"
    assert topic_key(0, "/joint_states", "sensor_msgs/msg/JointState", JOINT_STATE_HASH) == (
        f"0/joint_states/sensor_msgs::msg::dds_::JointState_/{JOINT_STATE_HASH}")
    assert topic_key(3, "/orccad/output/Stopping/", "std_msgs/msg/Empty", "RIHS01_x") == (
        "3/orccad/output/Stopping/std_msgs::msg::dds_::Empty_/RIHS01_x")
    gid = bytes(range(16))
    data = attachment(300, 1_500_000_000, gid)
    assert data[:16] == b"\x0fsequence_number" and data[16:24] == (300).to_bytes(8, "little")
    found = read_attachment(data)
    assert (found.sequence_number, found.source_timestamp_ns, found.source_gid) == (
        300, 1_500_000_000, gid)


def _free_port() -> int:
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]


def test_a_run_and_a_ros_2_peer_exchange_states_commands_inputs_and_outputs():
    zenoh = pytest.importorskip("zenoh", reason="the ros2 extra is not installed")
    from orccad_app.ros2 import messages
    from orccad_app.ros2.bridge import session_config

    store = messages.typestore()
    port = _free_port()
    endpoint = f"tcp/127.0.0.1:{port}"
    session = zenoh.open(session_config([], [endpoint]))
    states, outputs, lock = [], [], threading.Lock()

    def on_state(sample):
        with lock:
            states.append((sample.payload.to_bytes(), bytes(sample.attachment.to_bytes())))

    def on_output(sample):
        with lock:
            outputs.append(str(sample.key_expr))

    tokens = []  # (PUT or DELETE, key): the run's ROS 2 discovery (rmw_zenoh's liveliness)

    def on_token(sample):
        with lock:
            tokens.append((sample.kind == zenoh.SampleKind.PUT, str(sample.key_expr)))

    key = topic_key(0, "/joint_states", "sensor_msgs/msg/JointState", JOINT_STATE_HASH)
    subscribers = [session.declare_subscriber(key, on_state),
                   session.declare_subscriber("0/orccad/output/**", on_output),
                   session.liveliness().declare_subscriber("@ros2_lv/0/**", on_token)]
    run = subprocess.Popen([sys.executable, "-m", "orccad_app.cli", "run",
                            "missions/arm_recovery.orc", "--until", "12", "--realtime", "2",
                            "--ros2-zenoh", endpoint], stdout=subprocess.PIPE,
                           stderr=subprocess.PIPE, text=True)
    try:
        deadline = time.monotonic() + 90
        while time.monotonic() < deadline:  # until the run is 2 s in (simulated)
            with lock:
                latest = states[-1] if states else None
            if latest is not None and store.deserialize_cdr(
                    latest[0], "sensor_msgs/msg/JointState").header.stamp.sec >= 2:
                break
            assert run.poll() is None, run.communicate()
            time.sleep(0.05)
        else:
            raise AssertionError("no joint states from the run")
        command = messages.joint_state(0, ("j1", "j2", "j3"), [], [], [1.0, 2.0, 3.0])
        session.put(topic_key(0, "/joint_commands", "sensor_msgs/msg/JointState",
                              JOINT_STATE_HASH),
                    bytes(store.serialize_cdr(command, "sensor_msgs/msg/JointState")))
        empty = store.types["std_msgs/msg/Empty"](structure_needs_at_least_one_member=0)
        session.put(topic_key(0, "/orccad/input/Stop", "std_msgs/msg/Empty",
                              messages.type_hash("std_msgs/msg/Empty")),
                    bytes(store.serialize_cdr(empty, "std_msgs/msg/Empty")))
        out, err = run.communicate(timeout=120)
        deadline = time.monotonic() + 10
        while time.monotonic() < deadline:  # the tokens go with the run's session
            with lock:
                if any(not put for put, _ in tokens):
                    break
            time.sleep(0.05)
    finally:
        run.kill()
        for subscriber in subscribers:
            subscriber.undeclare()
        session.close()
    assert run.returncode == 0, err  # Stop: the arm parks, the mission is done
    assert "1 inputs raised, 1 joint commands applied" in err
    assert "no Zenoh router or peer" not in err  # this test's peer was reached
    message = store.deserialize_cdr(states[0][0], "sensor_msgs/msg/JointState")
    assert message.name == ["j1", "j2", "j3"] and len(message.position) == 3
    stamps = [read_attachment(a) for _, a in states]
    assert [s.sequence_number for s in stamps] == sorted({s.sequence_number for s in stamps})
    assert len({s.source_gid for s in stamps}) == 1
    assert stamps[0].source_timestamp_ns == (message.header.stamp.sec * 10**9
                                             + message.header.stamp.nanosec)
    stopping = [k for k in outputs if k.startswith("0/orccad/output/Stopping/")]
    assert stopping == [f"0/orccad/output/Stopping/std_msgs::msg::dds_::Empty_/"
                        f"{messages.type_hash('std_msgs/msg/Empty')}"]
    assert "Stop" in out  # the report's outputs and the park
    declared = {key for put, key in tokens if put}
    [node] = [key for key in declared if "/NN/" in key]
    zid = node.split("/")[2]
    assert node == f"@ros2_lv/0/{zid}/0/0/NN/%/%/orccad"
    entity = f"@ros2_lv/0/{zid}/0/[0-9]+/"
    expected = [
        rf"{entity}MP/%/%/orccad/%joint_states/sensor_msgs::msg::dds_::JointState_/"
        rf"{JOINT_STATE_HASH}/::,:,:,:,,",
        rf"{entity}MS/%/%/orccad/%joint_commands/sensor_msgs::msg::dds_::JointState_/"
        rf"{JOINT_STATE_HASH}/::,:,:,:,,",
        rf"{entity}MS/%/%/orccad/%orccad%input%Stop/std_msgs::msg::dds_::Empty_/RIHS01_\w+/"
        rf"::,:,:,:,,",
        rf"{entity}MP/%/%/orccad/%orccad%output%Stopping/std_msgs::msg::dds_::Empty_/"
        rf"RIHS01_\w+/::,:,:,:,,"]
    for pattern in expected:
        assert any(re.fullmatch(pattern, key) for key in declared), (pattern, declared)
    ids = [key.split("/")[4] for key in declared]
    assert len(ids) == len(set(ids))  # one id per entity
    assert (False, node) in tokens  # undeclared when the run ended


def test_without_the_extra_the_option_says_what_to_install():
    blocked = ("import sys; sys.modules['zenoh'] = None; from orccad_app.cli import main; "
               "sys.exit(main(['run', 'missions/arm_pid.orc', '--ros2-zenoh']))")
    result = subprocess.run([sys.executable, "-c", blocked], capture_output=True, text=True,
                            timeout=120)
    assert result.returncode == 2, result.stderr
    assert "--ros2-zenoh needs the ros2 extra: pip install -e '.[ros2]'" in result.stderr
    assert "Traceback" not in result.stderr and result.stdout == ""


@pytest.mark.parametrize("endpoint, said", [
    ("tcp/127.0.0.1:99999", "the port must be a whole number in [1, 65535], not '99999'"),
    ("tcp/127.0.0.1:0", "the port must be a whole number in [1, 65535], not '0'"),
    ("tcp/127.0.0.1:-1", "the port must be a whole number in [1, 65535], not '-1'"),
    ("tcp/127.0.0.1:abc", "the port must be a whole number in [1, 65535], not 'abc'"),
    ("tcp/127.0.0.1", "the address has no port"),
    ("tcp/:7447", "the address has no host"),
    ("garbage", "not an endpoint"),
    ("foo/1.2.3.4:7", "unknown protocol 'foo'"),
])
def test_a_bad_endpoint_is_a_located_error_before_the_file_is_read(endpoint, said, capsys):
    """Issue 34 item 8: on main a port of 99999, 0, -1 or abc ran the mission silently (Zenoh
    took the endpoint and never connected); 'garbage' printed Zenoh's Rust error with its
    source paths."""
    pytest.importorskip("zenoh", reason="the ros2 extra is not installed")
    from orccad_app.cli import main

    assert main(["run", "no-such-file.orc", "--ros2-zenoh", endpoint]) == 2
    err = capsys.readouterr().err
    assert f"orccad: error: --ros2-zenoh {endpoint}: {said}" in err
    assert "no-such-file" not in err and ".rs:" not in err


def test_good_endpoints_pass_and_zenoh_s_reason_loses_its_source_paths():
    from orccad_app.ros2.endpoint import check_endpoint, zenoh_reason

    for endpoint in ("tcp/127.0.0.1:7447", "tcp/[::1]:7447", "udp/router.local:7447",
                     "tcp/127.0.0.1:7447?iface=lo", "unixsock-stream//tmp/zenoh.sock"):
        assert check_endpoint(endpoint) == endpoint
    raw = ('Json5Err(Message { msg: "Endpoints must be of the form <protocol>/<address>: '
           'garbage at /root/.cargo/git/checkouts/zenoh/commons/endpoint.rs:615.", location: '
           'Some(Location { line: 1, column: 2 }) }) at /root/.cargo/zenoh/src/config.rs:86.')
    assert zenoh_reason(RuntimeError(raw)) == ("Endpoints must be of the form "
                                               "<protocol>/<address>: garbage")
    assert zenoh_reason(RuntimeError("invalid port value at /x/y/lib.rs:62.")) == \
        "invalid port value"


def test_a_run_with_no_router_or_peer_says_so_and_goes_on():
    """Issue 34 item 8: on main it said only '0 inputs raised, 0 joint commands applied'."""
    pytest.importorskip("zenoh", reason="the ros2 extra is not installed")
    endpoint = f"tcp/127.0.0.1:{_free_port()}"  # nobody there
    result = subprocess.run([sys.executable, "-m", "orccad_app", "run", "missions/arm_pid.orc",
                             "--until", "0.3", "--realtime", "100", "--ros2-zenoh", endpoint],
                            capture_output=True, text=True, timeout=120)
    assert result.returncode == 1, result.stderr  # the mission's own status: timeout
    assert (f"orccad: warning: --ros2-zenoh {endpoint}: no Zenoh router or peer reached"
            in result.stderr)
    assert (f"0 inputs raised, 0 joint commands applied; no Zenoh router or peer was reached "
            f"at {endpoint}") in result.stderr
