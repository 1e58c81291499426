"""The live observer: pacing, inputs raised on the executive's thread, updates (no Textual)."""

from __future__ import annotations

import os
import signal
import threading
import time
from pathlib import Path

import pytest

from orccad_app.tui.live import sensor_ports
from orccad_app.tui.pace import Pace
from orccad_app.tui.session import LiveSession, check_file, check_text, inspect_file


class _At:
    """Calls ``action()`` once, at the first reaction at or after ``t_ns``."""

    def __init__(self, t_ns, action):
        self.t_ns, self.action, self.done = t_ns, action, False

    def on_reaction(self, t_ns, inputs, outputs, status):
        if not self.done and t_ns >= self.t_ns:
            self.done = True
            self.action()


def _log(updates):
    return [entry.format().split(None, 2)[2] for update in updates for entry in update.log]


def test_a_run_reports_tasks_phases_samples_load_and_its_log():
    updates = []
    session = LiveSession("missions/arm_pid.orc", None, updates.append, speed=None)
    phases = []
    session.run.add_observer(_At(1_000_000_000, lambda: phases.append(session.run.phases)))
    result = session.execute()
    assert result.status == "done"
    assert phases == [{0: 3}]
    samples = {name for update in updates for name in update.samples}
    assert {"tracking error", "arm.q[0]", "arm.q[1]", "arm.q[2]"} <= samples
    assert updates[-1].misses == {} and 0.3 < updates[-1].loads["cpu0"] < 0.6
    assert _log(updates) == ["task      TrackPID (site 0) starts: q0=[0.5, 0.5, 0.5], kp=400, kv=40",
                             "output    Tracked",
                             "task      TrackPID (site 0) ends: good_end"]
    assert "mission ArmPID: done" in session.report()


def test_an_input_raised_by_the_user_reaches_the_automaton_at_the_next_reaction():
    updates = []
    session = LiveSession("missions/arm_recovery.orc", None, updates.append, speed=None)
    session.run.add_observer(_At(2_000_000_000, lambda: session.observer.raise_input("Stop")))
    result = session.execute()
    log = _log(updates)
    assert "input     Stop raised by the user" in log
    assert "task      TrackPID (site 2) ends: killed" in log
    assert [r.outcome for r in result.robot_tasks if r.name == "TrackPID"] == ["killed"]
    assert log.count("output    Beat") == 1  # a sustained output is logged once


def test_abort_ends_the_run_aborted():
    session = LiveSession("missions/arm_pid.orc", None, lambda update: None, speed=None)
    session.run.add_observer(_At(100_000_000, session.observer.abort))
    result = session.execute()
    assert (result.status, result.reason) == ("aborted", "stopped by the user")


def test_a_paused_run_waits_until_resumed():
    session = LiveSession("missions/arm_pid.orc", None, lambda update: None, speed=0)
    worker = threading.Thread(target=session.execute)
    worker.start()
    time.sleep(0.3)
    assert session.run.kernel.now == 0 and worker.is_alive()
    session.pace.set(None)
    worker.join(timeout=30)
    assert session.result.status == "done"


def test_pacing_follows_the_wall_clock():
    pace = Pace(10.0)
    start = time.perf_counter()
    for t_ms in range(0, 2001, 100):
        pace.wait(t_ms * 1_000_000)
    assert 0.18 < time.perf_counter() - start < 0.5
    with pytest.raises(ValueError):
        pace.set(-1)


def test_sensor_ports_name_the_robot_sensors_their_modules_read():
    session = LiveSession("missions/arm_pid.orc", None, lambda update: None)
    ports = sensor_ports(session.run.plan)
    assert ports[("TrackPID.ctrl", "q")] == "arm.q"
    assert ports[("TrackPID.ctrl", "qdot")] == "arm.qdot"


def test_the_trace_is_exported_after_the_run(tmp_path):
    session = LiveSession("missions/arm_pid.orc", None, lambda update: None, speed=None)
    session.execute()
    path = session.export(str(tmp_path / "run.csv"))
    lines = open(path, encoding="utf-8").read().splitlines()
    assert lines[0] == "time_ns,event,module,port,job,value" and len(lines) > 10_000


def test_a_file_with_an_error_shows_it_at_its_line(tmp_path):
    bad = tmp_path / "bad.orc"
    bad.write_text("robot arm : arm3dof;\nmission M {\n  emit ;\n}\n", encoding="utf-8")
    view = inspect_file(str(bad))
    assert not view.ok
    [diagnostic] = view.diagnostics
    assert (diagnostic.severity, diagnostic.line) == ("error", 3)


def test_the_compile_summary_and_check_come_from_the_cli_functions():
    view = inspect_file("missions/arm_recovery.orc")
    assert view.ok and view.missions == ["ArmRecovery"]
    assert view.inputs["ArmRecovery"] == ["Stop", "Hold", "Gripper"]
    summary = view.summaries["ArmRecovery"]
    assert "Robot-Tasks: Home, Park, TrackPID" in summary and "states" in summary
    text = check_text(check_file(view, "ArmRecovery"))
    assert "ok    built-in no-deadlock" in text and text.endswith("all properties hold")


def test_the_trace_is_exported_as_mcap_and_a_bad_suffix_is_refused(tmp_path):
    from mcap.reader import make_reader

    from orccad_app.diagnostics import OrccadError

    session = LiveSession("missions/arm_pid.orc", None, lambda update: None, speed=None)
    session.execute()
    csv_rows = len(open(session.export(str(tmp_path / "run.csv")), encoding="utf-8")
                   .read().splitlines()) - 1
    with open(session.export(str(tmp_path / "run.mcap")), "rb") as stream:
        topics = [channel.topic for _, channel, _ in make_reader(stream).iter_messages()]
    # every row: a write on its port's topic, any other event on /orccad/<event>
    assert sum(1 for t in topics if t.startswith(("/orccad/", "/ports/"))) == csv_rows
    assert "/plant/arm/q" in topics and "/log" in topics
    with pytest.raises(OrccadError):
        session.export(str(tmp_path / "run.txt"))


def test_the_export_of_an_aborted_run_ends_where_the_run_ended(tmp_path):
    """The live run records no trace: its export runs it again, aborted at the same
    reaction."""
    import csv

    from orccad_app.trace import CsvTraceWriter, TraceRecorder

    session = LiveSession("missions/arm_pid.orc", None, lambda update: None, speed=None)
    live = tmp_path / "live.csv"
    writer = CsvTraceWriter(live)
    session.run.add_observer(TraceRecorder(writer))
    session.run.add_observer(_At(300_000_000, session.observer.abort))
    result = session.execute()
    writer.close()
    assert result.status == "aborted"
    exported = tmp_path / "exported.csv"
    session.export(str(exported))
    assert exported.read_text() == live.read_text()
    with exported.open() as rows:
        last = list(csv.reader(rows))[-1]
    assert int(last[0]) <= result.sim_time_ns  # nothing after the reaction that ended it


def _kill_children() -> None:
    """SIGKILL this process's children (a run's process that hung: the test failed)."""
    me = os.getpid()
    for path in Path(f"/proc/{me}/task").glob("*/children"):
        for pid in path.read_text().split():
            os.kill(int(pid), signal.SIGKILL)


def test_a_run_forked_while_the_ui_changes_the_pace_never_inherits_its_lock_held():
    """The run's process is forked while another thread (the UI's) changes the pace: the
    child must never start with the pace's lock held, or it waits forever at its first
    reaction (a TUI pilot once timed out waiting for a pause)."""
    for attempt in range(12):
        session = LiveSession("missions/arm_pid.orc", None, lambda update: None, speed=100.0,
                              until_s=0.02, own_process=True)  # paced: the child waits
        stop = threading.Event()

        def change_the_pace(pace, stop):
            while not stop.is_set():
                pace.set(100.0)  # holds the pace's lock a moment

        changer = threading.Thread(target=change_the_pace, args=(session.pace, stop),
                                   daemon=True)
        changer.start()
        worker = threading.Thread(target=session.execute, daemon=True)
        worker.start()
        worker.join(timeout=30)
        stop.set()
        hung = worker.is_alive()
        if hung:
            _kill_children()
        changer.join(timeout=30)
        assert not hung, f"attempt {attempt}: the run's process never ended"
        assert session.result.status.value == "timeout"  # its horizon, 20 ms
