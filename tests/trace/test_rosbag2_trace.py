"""``orccad run --trace DIR --trace-format rosbag2`` (issue 26): a rosbag2 directory (MCAP
storage, CDR, ROS 2 Jazzy types and hashes) read back with ``rosbags`` message by message
against the MCAP trace of the same run (runs are deterministic: same seed, same messages)."""

from __future__ import annotations

import json
import subprocess
import sys
from collections import defaultdict

import pytest
from mcap.reader import make_reader

pytest.importorskip("rosbags", reason="the ros2 extra is not installed")

JOINT_STATE_HASH = "RIHS01_a13ee3a330e346c9d87b5aa18d24e11690752bd33a0350f11c5882bc9179260e"
"""sensor_msgs/msg/JointState's type hash in ROS 2 Jazzy (REP 2011)."""


def _run(*arguments: str) -> dict:
    result = subprocess.run([sys.executable, "-m", "orccad_app.cli", "run", *arguments,
                             "--json"], capture_output=True, text=True)
    assert result.returncode in (0, 1), result.stderr
    return json.loads(result.stdout)


def _bag(path):
    from rosbags.rosbag2 import Reader
    from rosbags.typesys import Stores, get_typestore

    store = get_typestore(Stores.ROS2_JAZZY)
    found = defaultdict(list)
    with Reader(path) as reader:
        connections = {c.topic: c for c in reader.connections}
        for connection, timestamp, data in reader.messages():
            found[connection.topic].append(
                (timestamp, store.deserialize_cdr(data, connection.msgtype)))
    custom = (path / "metadata.yaml").read_text(encoding="utf-8")
    return connections, found, custom


def _mcap(path):
    found = defaultdict(list)
    with open(path, "rb") as stream:
        for _, channel, message in make_reader(stream).iter_messages(log_time_order=False):
            found[channel.topic].append((message.log_time, json.loads(message.data)))
    return found


def _same(topic: str, bagged, traced) -> None:
    """One bag message against the MCAP message of the same topic and instant."""
    kind = type(bagged).__msgtype__
    if kind == "rcl_interfaces/msg/Log":
        assert bagged.msg == traced["message"] and bagged.level == 10 * traced["level"]
        assert (bagged.stamp.sec, bagged.stamp.nanosec) == tuple(traced["timestamp"].values())
    elif kind == "tf2_msgs/msg/TFMessage":
        assert len(bagged.transforms) == len(traced["transforms"])
        for got, want in zip(bagged.transforms, traced["transforms"]):
            assert (got.header.frame_id, got.child_frame_id) == (want["parent_frame_id"],
                                                                want["child_frame_id"])
            t, r = got.transform.translation, got.transform.rotation
            assert (t.x, t.y, t.z) == tuple(want["translation"].values())
            assert (r.x, r.y, r.z, r.w) == tuple(want["rotation"].values())
    elif kind == "std_msgs/msg/Float64MultiArray":
        value = traced["value"]
        assert bagged.data.tolist() == (value if isinstance(value, list) else [value]), topic
    elif kind == "std_msgs/msg/Int8":
        assert bagged.data == traced["value"], topic
    else:
        assert kind == "std_msgs/msg/String", topic
        assert bagged.data in (traced.get("value"), json.dumps(traced, separators=(",", ":")))


def _compare(bag_path, mcap_path) -> tuple[dict, dict]:
    connections, bagged, custom = _bag(bag_path)
    traced = _mcap(mcap_path)
    renamed = {"/log": "/rosout"}
    for topic, messages in traced.items():
        if topic == "/scene":
            assert "/scene" not in bagged  # no ROS 2 message for it
            continue
        got = bagged[renamed.get(topic, topic)]
        assert [t for t, _ in got] == [t for t, _ in messages], topic
        for (_, bag_message), (_, mcap_message) in zip(got, messages):
            _same(topic, bag_message, mcap_message)
    assert set(bagged) - {renamed.get(t, t) for t in traced} <= {"/joint_states", "/auv/pose"}
    return connections, bagged | {"custom": custom}


def test_an_arm_run_as_a_rosbag2_reads_back_message_by_message(tmp_path, recovery_run):
    bag = tmp_path / "recovery_bag"
    report = _run("missions/arm_recovery.orc", "--inject", "Stop@3", "--until", "4",
                  "--trace", str(bag), "--trace-format", "rosbag2")
    assert {k: v for k, v in report.items() if k != "wall_time_s"} == {
        k: v for k, v in recovery_run.report.items() if k != "wall_time_s"}  # the same run
    assert sorted(p.name for p in bag.iterdir()) == ["metadata.yaml", "recovery_bag.mcap"]
    connections, bagged = _compare(bag, recovery_run.path)
    joint_states = connections["/joint_states"]
    assert joint_states.msgtype == "sensor_msgs/msg/JointState"
    assert joint_states.digest == JOINT_STATE_HASH
    assert "orccad.mission: ArmRecovery" in bagged["custom"]  # metadata.yaml's custom_data
    # a joint state at every instant a module read the arm's sensors: positions and
    # velocities are the sensors' values there (no noise configured), effort the torques
    states = {t: m for t, m in bagged["/joint_states"]}
    traced = _mcap(recovery_run.path)
    for sensor, field in (("/plant/arm/q", "position"), ("/plant/arm/qdot", "velocity")):
        for time_ns, message in traced[sensor]:
            assert getattr(states[time_ns], field).tolist() == message["value"], time_ns
    first = next(iter(states.values()))
    assert first.name == ["j1", "j2", "j3"] and len(first.effort) == 3
    assert len(states) >= len(traced["/plant/arm/q"]) > 3000


def test_an_auv_run_as_a_rosbag2_has_its_pose_and_frames(tmp_path):
    bag, trace = tmp_path / "survey_bag", tmp_path / "survey.mcap"
    arguments = ("missions/auv_survey.orc", "--until", "8")
    _run(*arguments, "--trace", str(bag), "--trace-format", "rosbag2")
    _run(*arguments, "--trace", str(trace))
    connections, bagged = _compare(bag, trace)
    assert connections["/auv/pose"].msgtype == "geometry_msgs/msg/PoseStamped"
    assert connections["/tf"].msgtype == "tf2_msgs/msg/TFMessage"
    poses, frames = bagged["/auv/pose"], bagged["/tf"]
    assert len(poses) == len(frames) > 100  # every 20 ms that the plant's state moved on
    for (t_pose, pose), (t_frame, frame) in zip(poses, frames):
        hull = frame.transforms[0]
        assert t_pose == t_frame and hull.child_frame_id == "auv/hull"
        assert pose.header.frame_id == "world"
        p = pose.pose.position
        assert (p.x, p.y, p.z) == (hull.transform.translation.x, hull.transform.translation.y,
                                   hull.transform.translation.z)
    depths = [-p.pose.position.z for _, p in poses]
    assert max(depths) - min(depths) > 0.01  # it moves (the dive starts at 7 s)


def test_without_the_extra_the_format_says_what_to_install(tmp_path):
    blocked = ("import sys; sys.modules['rosbags'] = None; sys.modules['rosbags.rosbag2'] = None;"
               " from orccad_app.cli import main; sys.exit(main(['run', 'missions/arm_pid.orc',"
               f" '--trace', r'{tmp_path / 'bag'}', '--trace-format', 'rosbag2']))")
    result = subprocess.run([sys.executable, "-c", blocked], capture_output=True, text=True,
                            timeout=120)
    assert result.returncode == 2, result.stderr
    assert "pip install -e '.[ros2]'" in result.stderr and "Traceback" not in result.stderr
    assert not (tmp_path / "bag").exists()


def test_an_existing_directory_is_refused_before_the_run(tmp_path):
    result = subprocess.run([sys.executable, "-m", "orccad_app.cli", "run",
                             "missions/arm_pid.orc", "--trace", str(tmp_path),
                             "--trace-format", "rosbag2"], capture_output=True, text=True,
                            timeout=120)
    assert result.returncode == 2 and "exists already" in result.stderr, result.stderr
