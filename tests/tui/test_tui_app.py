"""Pilots: the whole app driven as a person would, asserting on screens and messages."""

from __future__ import annotations

import asyncio
import io
import functools
import time
from pathlib import Path

from rich.console import Console

from orccad_app.tui.app import OrccadApp
from orccad_app.tui.messages import InputRequested, RunFinished
from orccad_app.tui.screens.browser import BrowserScreen
from orccad_app.tui.screens.report import ReportScreen
from orccad_app.tui.screens.run import RunScreen

SIZE = (160, 48)
AUV = Path("missions/auv_survey.orc")


def pilot_test(scenario):
    """Run an ``async`` pilot scenario as a plain test (no asyncio plugin needed)."""
    @functools.wraps(scenario)
    def test(*args, **kwargs):
        asyncio.run(scenario(*args, **kwargs))
    return test


def _text(screen, selector: str) -> str:
    """The plain text of a ``Static``'s content (a string or a Rich renderable)."""
    widget = screen.query_one(selector)
    if hasattr(widget, "text"):  # a TextArea
        return widget.text
    content = widget.content
    if isinstance(content, str):
        return content
    console = Console(width=200, record=True, file=io.StringIO())
    console.print(content)
    return console.export_text()


async def _until(pilot, condition, timeout: float = 30.0, describe=None) -> None:
    """Wait until ``condition()``; ``describe()`` says what was seen instead, on a timeout."""
    start = time.monotonic()
    while not condition():
        assert time.monotonic() - start < timeout, \
            f"timed out waiting for the UI{': ' + describe() if describe else ''}"
        await pilot.pause(0.05)
    await pilot.pause(0.1)  # let a screen just pushed finish mounting (its Header's title)


def _report_shown(app) -> bool:
    """The report screen is up and composed."""
    return isinstance(app.screen, ReportScreen) and bool(app.screen.query("#report-text"))


def _log(screen) -> list[str]:
    return [entry.format() for entry in screen.query_one("#log").entries]


@pilot_test
async def test_the_browser_shows_source_diagnostics_summary_and_check():
    app = OrccadApp(["missions/arm_recovery.orc"], selected="missions/arm_recovery.orc")
    async with app.run_test(size=SIZE) as pilot:
        screen = app.screen
        assert isinstance(screen, BrowserScreen)
        assert "missions/arm_pid.orc" in screen.files  # missions/ is always listed
        assert "no diagnostics" in _text(screen, "#source-view")
        await pilot.press("m")
        summary = _text(screen, "#summary-text")
        assert "mission ArmRecovery" in summary and "Robot-Tasks: Home, Park, TrackPID" in summary
        assert "declared inputs: Stop, Hold, Gripper" in summary
        await pilot.press("c")
        await _until(pilot, lambda: "all properties hold" in _text(screen, "#check-text"))
        assert "built-in no-deadlock" in _text(screen, "#check-text")


@pilot_test
async def test_a_file_with_an_error_is_shown_with_it_and_cannot_run(tmp_path):
    bad = tmp_path / "bad.orc"
    bad.write_text("robot arm : arm3dof;\nmission M {\n  emit ;\n}\n", encoding="utf-8")
    app = OrccadApp([str(bad)], selected=str(bad))
    async with app.run_test(size=SIZE) as pilot:
        assert "3:" in _text(app.screen, "#source-view")
        assert "error" in _text(app.screen, "#source-view")
        await pilot.press("r")
        assert isinstance(app.screen, BrowserScreen)


@pilot_test
async def test_an_arm_run_goes_live_to_its_report_and_exports_its_trace(tmp_path):
    app = OrccadApp(["missions/arm_pid.orc"], selected="missions/arm_pid.orc", speed=None)
    finished = []
    async with app.run_test(size=SIZE, message_hook=lambda m: isinstance(
            m, RunFinished) and finished.append(m)) as pilot:
        await pilot.press("r")
        await _until(pilot, lambda: _report_shown(app))
        report = app.screen
        assert "mission ArmPID: done" in _text(report, "#report-text")
        assert "TrackPID(q0=[0.5, 0.5, 0.5], kp=400, kv=40) 0.000 → 4.000 s  good_end" in \
            _text(report, "#report-text")
        assert {m.result.status for m in finished} == {"done"}
        assert len({id(m) for m in finished}) == 1
        report.query_one("#export-path").value = str(tmp_path / "arm.mcap")
        await pilot.press("e")
        await _until(pilot, lambda: (tmp_path / "arm.mcap").exists() and not report.exporting)
        assert (tmp_path / "arm.mcap").stat().st_size > 1000
        await pilot.press("escape")
        run = app.screen
        assert isinstance(run, RunScreen) and run.finished
        assert "mission ArmPID done" in _text(run, "#run-status")
        assert {"tracking error", "arm.q[0]", "arm.q[1]", "arm.q[2]"} <= set(
            run.query_one("#plots").series)
        assert "deadline misses" in str(run.query_one("#load").get_row_at(1))
        assert _log(run)[-1].endswith("status    mission done")
        await pilot.press("escape")
        assert isinstance(app.screen, BrowserScreen)


@pilot_test
async def test_a_key_raises_a_declared_input_during_the_run_and_the_mission_recovers():
    # half speed: TrackPID's 4 s last 8 s of wall time, so a screen lagging behind the run on
    # a loaded machine still shows TrackPID running when the key is pressed
    app = OrccadApp([], selected="missions/arm_recovery.orc", speed=0.5, run_now=True)
    requested = []
    async with app.run_test(size=SIZE, message_hook=lambda m: isinstance(
            m, InputRequested) and requested.append(m)) as pilot:
        await pilot.pause()
        run = app.screen
        assert isinstance(run, RunScreen)
        await _until(pilot, lambda: any("TrackPID (site 2) starts" in line
                                        for line in _log(run)))
        await pilot.press("1")  # Stop: abort the tracking, park the arm
        await pilot.press("m")  # then as fast as possible
        await _until(pilot, lambda: _report_shown(app))
        assert [m.name for m in {id(m): m for m in requested}.values()] == ["Stop"]
        report = _text(app.screen, "#report-text")
        assert "mission ArmRecovery: done" in report and "killed" in report
        log = _log(run)
        assert any("input     Stop raised by the user" in line for line in log)
        assert any("TrackPID (site 2) ends: killed" in line for line in log)
        assert any("Park (site 1) starts" in line for line in log)
        assert any("Park (site 1) ends: good_end" in line for line in log)


@pilot_test
async def test_keys_after_the_declared_inputs_raise_observer_events():
    # missions/arm_pid.orc declares no input: keys 1-3 raise TrackPID's observer events
    app = OrccadApp([], selected="missions/arm_pid.orc", speed=0.5, run_now=True)
    async with app.run_test(size=SIZE) as pilot:
        await pilot.pause()
        run = app.screen
        assert run.query_one("#inputs").keyed == [
            "TrackPID.JointLimit", "TrackPID.TrackingLost", "TrackPID.Saturated"]
        await _until(pilot, lambda: run.last is not None and run.last.time_ns > 200_000_000)
        await pilot.press("2")
        await _until(pilot, lambda: _report_shown(app))
        assert "mission ArmPID: failed (TrackingLost)" in _text(app.screen, "#report-text")
        assert any("input     TrackPID.TrackingLost raised by the user" in line
                   for line in _log(run))


@pilot_test
async def test_the_log_filter_keeps_matching_lines():
    app = OrccadApp([], selected="missions/arm_pid.orc", speed=None, run_now=True)
    async with app.run_test(size=SIZE) as pilot:
        await _until(pilot, lambda: _report_shown(app))
        await pilot.press("escape")
        run = app.screen
        run.query_one("#log-filter").value = "output"
        await pilot.pause()
        assert [e.text for e in run.query_one("#log").shown()] == ["Tracked"]


@pilot_test
async def test_pause_and_speed_keys_drive_the_pacing(tmp_path):
    # a 60 s tracking: a key press in a pilot may wait up to 2 s while the run works
    long = tmp_path / "long.orc"
    long.write_text(Path("missions/arm_pid.orc").read_text(encoding="utf-8")
                    .replace("duration 4 s", "duration 60 s"), encoding="utf-8")
    app = OrccadApp([], selected=str(long), speed=1.0, run_now=True)
    async with app.run_test(size=SIZE) as pilot:
        await pilot.pause()
        run = app.screen
        await pilot.press("x")
        assert run.session.pace.label == "10×"
        await pilot.press("space")
        assert run.session.pace.label == "paused"
        # the run (in its own process) stops at its next reaction and shows where it stopped
        await _until(pilot, lambda: run.last is not None and run.last.speed == "paused",
                     describe=lambda: f"last frame {run.last and (run.last.time_ns, run.last.speed)}")
        now = run.last.time_ns
        await pilot.pause(0.2)
        assert run.last.time_ns == now
        await pilot.press("space")
        assert run.session.pace.label == "10×"
        await pilot.press("r")
        assert run.session.pace.label == "1×"
        await pilot.press("a")
        await _until(pilot, lambda: _report_shown(app))
        assert "mission ArmPID: aborted" in _text(app.screen, "#report-text")


@pilot_test
async def test_an_auv_run_with_an_injected_fault():
    """The shipped AUV mission runs in the TUI with its plant's leak fault (a planning error
    fails the test: the AUV plugin ships with the product)."""
    app = OrccadApp([], selected=str(AUV), speed=0, run_now=True)
    async with app.run_test(size=SIZE) as pilot:
        await pilot.pause()
        run = app.screen
        assert isinstance(run, RunScreen)
        run.query_one("#injection").value = "auv.leak"
        run.query_one("#input-value").value = "1"
        await pilot.press("i")  # queued while paused: applied at the first reaction
        await pilot.press("m")
        await _until(pilot, lambda: _report_shown(app), timeout=60)
        log = _log(run)
        assert any("fault     auv.leak=1.0 injected by the user" in line for line in log)
        assert any("exception Leak (type 3)" in line for line in log)
        report = _text(app.screen, "#report-text")
        assert "mission AuvSurvey: aborted (Leak)" in report
        assert {"auv.depth", "auv.attitude[2]"} <= set(run.query_one("#plots").series)
