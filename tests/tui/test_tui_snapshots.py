"""Snapshots of the main screens (pytest-textual-snapshot; update with --snapshot-update).

The app runs in a scratch folder holding one fixed mission, so the snapshots do not change
when ``missions/`` does.
"""

from __future__ import annotations

import pytest

from orccad_app.tui.app import OrccadApp

pytest.importorskip("pytest_textual_snapshot")

SIZES = {"80x24": (80, 24), "160x48": (160, 48)}
"""The smallest terminal the console supports, and a large one."""
MISSION = """\
// A PID tracking of the cosine trajectory on the 3-DOF arm (snapshot fixture).
robot arm : arm3dof;

robottask TrackPID(kp: float = 400.0) on arm {
    duration 4 s;
    task_function joint_tracking(trajectory = cosine(q0 = [0.5, 0.5, 0.5], omega = pi));
    law pid(kp = kp, kv = 40.0, ki = 10.0);
    module traj : trajectory  period 1 ms wcet 0.1 ms on cpu0 priority 2;
    module ctrl : control_law period 1 ms wcet 0.3 ms on cpu0 priority 1;
    connect traj.qd     -> ctrl.qd;
    connect traj.qd_dot -> ctrl.qd_dot;
    connect arm.q       -> ctrl.q;
    connect arm.qdot    -> ctrl.qdot;
    connect ctrl.tau    -> arm.tau;
    exception TrackingLost from tracking_error(max = 0.2) : abort;
}

mission Snap {
    input Stop;
    output Tracked;
    abort {
        run TrackPID();
        emit Tracked;
    } when Stop;
}
"""


@pytest.fixture
def scratch(tmp_path, monkeypatch):
    (tmp_path / "snap.orc").write_text(MISSION, encoding="utf-8")
    monkeypatch.chdir(tmp_path)
    return "snap.orc"


async def _first_update(pilot) -> None:
    """The run screen has shown the first reaction (the run is paused there)."""
    for _ in range(400):
        screen = pilot.app.screen
        if getattr(screen, "last", None) is not None:
            break
        await pilot.pause(0.05)
    await pilot.pause(0.3)


@pytest.mark.parametrize("size", SIZES)
def test_browser_source(snap_compare, scratch, size):
    assert snap_compare(OrccadApp([scratch], selected=scratch), terminal_size=SIZES[size])


@pytest.mark.parametrize("size", SIZES)
def test_browser_summary(snap_compare, scratch, size):
    assert snap_compare(OrccadApp([scratch], selected=scratch), press=["m"],
                        terminal_size=SIZES[size])


@pytest.mark.parametrize("size", SIZES)
def test_help(snap_compare, scratch, size):
    assert snap_compare(OrccadApp([scratch], selected=scratch), press=["question_mark"],
                        terminal_size=SIZES[size])


@pytest.mark.parametrize("size", SIZES)
def test_editor(snap_compare, scratch, size):
    async def edit(pilot):
        await pilot.press("ctrl+e")
        await pilot.pause(1.5)  # the diagnostics, compiled in a worker
        from textual.widgets import TextArea
        pilot.app.screen.query_one(TextArea).cursor_blink = False  # a blink is a race
        await pilot.pause()
    assert snap_compare(OrccadApp([scratch], selected=scratch), run_before=edit,
                        terminal_size=SIZES[size])


@pytest.mark.parametrize("size", SIZES)
def test_run_screen_paused_at_start(snap_compare, scratch, size):
    app = OrccadApp([scratch], selected=scratch, speed=0, run_now=True)
    assert snap_compare(app, run_before=_first_update, terminal_size=SIZES[size])


@pytest.mark.parametrize("size", SIZES)
def test_run_screen_source_tab(snap_compare, scratch, size):
    async def source(pilot):
        await _first_update(pilot)
        await pilot.press("o")
        await pilot.pause(0.2)
    app = OrccadApp([scratch], selected=scratch, speed=0, run_now=True)
    assert snap_compare(app, run_before=source, terminal_size=SIZES[size])


def test_empty_state(snap_compare, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert snap_compare(OrccadApp([]), terminal_size=SIZES["80x24"])


@pytest.fixture
def failing(tmp_path, monkeypatch):
    """The fixture mission with a property its run violates (a counterexample to replay)."""
    (tmp_path / "cex.orc").write_text(MISSION + "\nproperty Snap.never_tracked: never Tracked;\n",
                                      encoding="utf-8")
    monkeypatch.chdir(tmp_path)
    return "cex.orc"


async def _checked(pilot) -> None:
    await pilot.press("c")
    for _ in range(400):
        if getattr(pilot.app.screen, "report", None) is not None:
            break
        await pilot.pause(0.05)
    await pilot.pause(0.3)
    pilot.app.clear_notifications()  # a toast times out: a race in a snapshot
    await pilot.pause()


@pytest.mark.parametrize("size", SIZES)
def test_check_tab_with_a_counterexample(snap_compare, failing, size):
    assert snap_compare(OrccadApp([failing], selected=failing), run_before=_checked,
                        terminal_size=SIZES[size])


@pytest.mark.parametrize("size", SIZES)
def test_counterexample_replay(snap_compare, failing, size):
    async def replay(pilot):
        await _checked(pilot)
        await pilot.press("enter")  # its first instant: TrackPID runs, the mission waits in it
        await pilot.pause(0.3)
    assert snap_compare(OrccadApp([failing], selected=failing), run_before=replay,
                        terminal_size=SIZES[size])
