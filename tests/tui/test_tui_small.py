"""The console at 80×24 as a new user meets it from docs/tui.md (issue 18's audit): nothing
falls off-screen, file names stay distinguishable, the status line says what runs even when
the mission waits at many statements, the palette offers the screen's own commands first."""

from __future__ import annotations

from types import SimpleNamespace

from orccad_app.diagnostics import SourceLocation
from orccad_app.tui.app import OrccadApp
from orccad_app.tui.commands import commands_for
from orccad_app.tui.screens.run import RunScreen
from orccad_app.tui.status import MAX_WAITING, where_text
from orccad_app.tui.widgets.inputs import InputBar
from orccad_app.tui.widgets.tables import LoadTable, TaskTable

from tests.tui.test_tui_app import _report_shown, _until, pilot_test

SMALL = (80, 24)
RECOVERY = "missions/arm_recovery.orc"


@pilot_test
async def test_the_run_screen_keeps_every_part_on_an_80x24_terminal():
    app = OrccadApp([], selected=RECOVERY, speed=0, run_now=True)
    async with app.run_test(size=SMALL) as pilot:
        await pilot.pause()
        run = app.screen
        assert isinstance(run, RunScreen)
        await _until(pilot, lambda: run.last is not None)
        bar = run.query_one(InputBar)
        for part in bar.children:  # the mode, the inputs, the value, the list, inject
            assert part.region.width > 0 and part.region.right <= SMALL[0], part
        assert bar.query_one("#inject").region.right <= SMALL[0]
        for table in (run.query_one(TaskTable), run.query_one(LoadTable)):
            assert table.virtual_size.width <= table.size.width, table  # no sideways scroll
        keys = [key for key in run.query("FooterKey") if key.region.width]
        assert {key.key for key in keys} >= {"space", "i", "h", "a", "question_mark"}
        assert all(key.region.right <= SMALL[0] for key in keys)
        await pilot.press("a")
        await _until(pilot, lambda: _report_shown(app))


@pilot_test
async def test_the_narrow_mission_list_tells_similar_files_apart():
    app = OrccadApp([], selected=RECOVERY)
    async with app.run_test(size=SMALL) as pilot:
        await pilot.pause()
        labels = [str(item.query_one("Label").content) for item in app.screen.query(
            "#files ListItem")]
        assert "arm_pid.orc" in labels and not any(x.startswith("missions/") for x in labels)
        first = app.screen.query_one("#files ListItem Label")
        assert first.styles.text_overflow == "ellipsis" and first.styles.text_wrap == "nowrap"
        # the list still holds the paths: enter opens the file
        assert app.screen.query_one("#files ListItem").name.startswith("missions/")


def _session(waiting: int):
    """A stand-in run whose state waits at ``waiting`` statements while TrackPID runs."""
    locs = tuple(SourceLocation("m.orc", line, 1) for line in range(10, 10 + waiting))
    label = SimpleNamespace(site=2, task="TrackPID")
    site = SimpleNamespace(number=2, task="TrackPID",
                           site=SimpleNamespace(stmt=SimpleNamespace(
                               loc=SourceLocation("m.orc", 48, 5))))
    automaton = SimpleNamespace(waiting=(locs,), labels=((label,),))
    return SimpleNamespace(path="m.orc", automaton=automaton, run=SimpleNamespace(
        plan=SimpleNamespace(automaton=automaton, sites=[site])))


def test_a_long_wait_list_is_cut_after_the_running_tasks():
    short = where_text(_session(2), 0)
    assert short == "waiting at m.orc:10, 11 (running TrackPID at :48)"
    long = where_text(_session(MAX_WAITING + 5), 0)
    assert long.startswith("running TrackPID at :48; waiting at m.orc:10, 11")
    assert long.endswith("13 … +5") and len(long) < 80


@pilot_test
async def test_the_palette_offers_the_screens_own_commands_first():
    app = OrccadApp([], selected=RECOVERY, speed=0, run_now=True)
    async with app.run_test(size=SMALL) as pilot:
        await pilot.pause()
        run = app.screen
        await _until(pilot, lambda: run.last is not None)
        titles = [title for title, _, _ in commands_for(app, run)]
        first_open = next(i for i, t in enumerate(titles) if t.startswith("Open mission"))
        assert titles.index("Raise input Stop") < first_open
        assert titles.index("Abort the run") < first_open
        await pilot.press("a")
        await _until(pilot, lambda: _report_shown(app))
