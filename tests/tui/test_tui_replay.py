"""From proof to run in the console (issue 18): a counterexample of the Check tab replayed
step by step — where the mission waits at each instant, the failing instant marked — and run
against the plant with its inputs injected (the run screen, then the report listing them)."""

from __future__ import annotations

from pathlib import Path

from orccad_app.tui.app import OrccadApp
from orccad_app.tui.commands import commands_for
from orccad_app.tui.screens.browser import BrowserScreen
from orccad_app.tui.screens.replay import ReplayScreen
from orccad_app.tui.screens.run import RunScreen
from orccad_app.verify.replay import FAILS, LOOPS

from tests.tui.test_tui_app import _log, _report_shown, _text, _until, pilot_test

FALSE = "missions/false_property.orc"
SMALL = (80, 24)


def _line_of(text: str) -> int:
    return next(n for n, line in enumerate(Path(FALSE).read_text().splitlines(), 1)
                if text in line)


async def _checked(pilot, app) -> BrowserScreen:
    browser = app.screen
    assert isinstance(browser, BrowserScreen)
    await pilot.press("c")
    await _until(pilot, lambda: browser.report is not None)
    return browser


@pilot_test
async def test_a_counterexample_is_replayed_step_by_step_where_the_mission_waits():
    app = OrccadApp([FALSE], selected=FALSE, speed=None)
    async with app.run_test(size=SMALL) as pilot:
        browser = await _checked(pilot, app)
        listed = browser.query_one("#counterexamples")
        assert listed.display and listed.option_count == 2  # the two failed properties
        await pilot.press("enter")  # the first: placed_after_approach
        await _until(pilot, lambda: isinstance(app.screen, ReplayScreen))
        replay = app.screen
        assert "instant 1 of 4" in _text(replay, "#replay-status")
        source = replay.query_one("#replay-source")
        assert source.waiting == [_line_of("await Go;")]  # highlighted as on the run screen
        await pilot.press("right")
        step = _text(replay, "#replay-step")
        assert "inputs:  Go" in step and "Approach.start" in step
        assert source.sites == [_line_of("run Approach();")]  # the running task's run line
        await pilot.press("right")
        assert "Approach.TrackingLost" in _text(replay, "#replay-step")
        await pilot.press("left")
        assert replay.index == 1 and "inputs:  Go" in _text(replay, "#replay-step")
        await pilot.press("f")  # to the failing instant
        status = _text(replay, "#replay-status")
        assert replay.index == 3 and "instant 4 of 4" in status and FAILS in status
        assert "Placed" in _text(replay, "#replay-step")
        assert "ended: done" in _text(replay, "#replay-step")
        await pilot.press("right")  # stays on the last instant
        assert replay.index == 3
        await pilot.press("escape")
        assert app.screen is browser
        await pilot.press("down", "enter")  # the liveness one: its loop is marked
        await _until(pilot, lambda: isinstance(app.screen, ReplayScreen))
        await pilot.press("f")
        assert LOOPS in _text(app.screen, "#replay-status")


@pilot_test
async def test_a_counterexample_runs_against_the_plant_with_its_inputs_injected():
    app = OrccadApp([FALSE], selected=FALSE, speed=None)
    async with app.run_test(size=SMALL) as pilot:
        await _checked(pilot, app)
        await pilot.press("p")  # replay the chosen one
        await _until(pilot, lambda: isinstance(app.screen, ReplayScreen))
        await pilot.press("r")  # run it against the plant
        await _until(pilot, lambda: isinstance(app.screen, RunScreen)
                     or _report_shown(app))
        run = next(s for s in app.screen_stack if isinstance(s, RunScreen))
        assert run.session.script is not None
        assert "counterexample to placed_after_approach" in run.sub_title
        await _until(pilot, lambda: _report_shown(app), timeout=60)
        report = _text(app.screen, "#report-text")
        assert "0.001 s  Go (input, counterexample to placed_after_approach)" in report
        assert ("0.002 s  Approach.TrackingLost (input, counterexample to "
                "placed_after_approach)") in report
        assert "false     LTL    placed_after_approach" in report  # violated on the plant
        log = _log(run)
        assert any("Go raised by the counterexample to placed_after_approach" in line
                   for line in log)


@pilot_test
async def test_the_palette_offers_to_replay_and_to_run_each_counterexample():
    app = OrccadApp([FALSE], selected=FALSE, speed=None)
    async with app.run_test(size=SMALL) as pilot:
        browser = await _checked(pilot, app)
        titles = {title: callback for title, callback, _ in commands_for(app, browser)}
        assert "Replay the counterexample to eventually_placed" in titles
        titles["Run the counterexample to placed_after_approach against the plant"]()
        await _until(pilot, lambda: isinstance(app.screen, RunScreen) or _report_shown(app))
        run = next(s for s in app.screen_stack if isinstance(s, RunScreen))
        assert [(r.name, r.time_ns) for r in run.session.scripted] == [
            ("Go", 1_000_000), ("Approach.TrackingLost", 2_000_000)]
        await _until(pilot, lambda: _report_shown(app), timeout=60)
