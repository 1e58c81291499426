"""Regenerate the terminal UI's screenshots in docs/ (SVG exported by the app itself).

Run from the repository root: ``python docs/make_screenshots.py``. Writes
``docs/tui-browser.svg`` (the mission browser), ``docs/tui-check.svg`` (``orccad check``
results), ``docs/tui-run.svg`` (a live run of missions/arm_recovery.orc, paused while the
tracking runs), ``docs/tui-report.svg`` (its report after ``Stop`` was raised) and, when the
AUV mission plans, ``docs/tui-auv.svg`` (the AUV survey after a leak); the run screen's tabs
``tui-run-source.svg``, ``tui-run-rta.svg``, ``tui-run-tcs.svg``, the help ``tui-help.svg``,
the run at 80×24 ``tui-run-80x24.svg``, the editor with a diagnostic ``tui-editor.svg`` and a
counterexample of missions/false_property.orc replayed ``tui-replay.svg``, and the campaign
screen after 16 runs of missions/auv_survey.campaign.toml ``tui-campaign.svg``
(``python docs/make_screenshots.py campaign`` makes that one only).
The snapshot tests (``tests/tui/__snapshots__``) hold the same screens at 80×24 and 160×48.
"""

from __future__ import annotations

import asyncio
import sys
import tempfile
import time
from pathlib import Path

from orccad_app.tui.app import OrccadApp
from orccad_app.tui.screens.report import ReportScreen

DOCS = Path(__file__).resolve().parent
SIZE = (150, 44)


async def _until(pilot, condition, timeout: float = 60.0) -> None:
    start = time.monotonic()
    while not condition():
        if time.monotonic() - start > timeout:
            raise TimeoutError("the UI did not get there in time")
        await pilot.pause(0.05)


def _report_shown(app) -> bool:
    return isinstance(app.screen, ReportScreen) and bool(app.screen.query("#report-text"))


def _logged(screen, text: str) -> bool:
    return any(text in entry.format() for entry in screen.query_one("#log").entries)


async def browser() -> None:
    app = OrccadApp(["missions/arm_recovery.orc"], selected="missions/arm_recovery.orc")
    async with app.run_test(size=SIZE) as pilot:
        app.save_screenshot("tui-browser.svg", str(DOCS))
        await pilot.press("c")
        await _until(pilot, lambda: "hold" in str(app.screen.query_one("#check-text").content))
        await pilot.pause(0.5)
        app.save_screenshot("tui-check.svg", str(DOCS))


async def arm_run() -> None:
    app = OrccadApp([], selected="missions/arm_recovery.orc", speed=1.0, run_now=True)
    async with app.run_test(size=SIZE) as pilot:
        run = app.screen
        await _until(pilot, lambda: _logged(run, "TrackPID (site 2) starts"))
        await pilot.pause(1.0)
        await pilot.press("space")
        await pilot.pause(0.5)
        app.save_screenshot("tui-run.svg", str(DOCS))
        for key, name in (("o", "tui-run-source.svg"), ("e", "tui-run-rta.svg"),
                          ("t", "tui-run-tcs.svg")):
            await pilot.press(key)
            await pilot.pause(0.3)
            app.save_screenshot(name, str(DOCS))
        await pilot.press("g", "question_mark")
        await pilot.pause(0.3)
        app.save_screenshot("tui-help.svg", str(DOCS))
        await pilot.press("escape")
        await pilot.press("1", "m")  # Stop, then as fast as possible
        await _until(pilot, lambda: _report_shown(app))
        await pilot.pause(0.5)
        app.save_screenshot("tui-report.svg", str(DOCS))


async def auv_run() -> None:
    app = OrccadApp([], selected="missions/auv_survey.orc", speed=None, run_now=True)
    async with app.run_test(size=SIZE) as pilot:
        run = app.screen
        if isinstance(run, ReportScreen) or not hasattr(run, "session"):
            return
        await _until(pilot, lambda: _logged(run, "Dive (site 1) starts"))
        run.query_one("#injection").value = "auv.leak"
        run.query_one("#input-value").value = "1"
        await pilot.press("i")
        await _until(pilot, lambda: _report_shown(app))
        await pilot.press("escape")
        await pilot.pause(0.5)
        app.save_screenshot("tui-auv.svg", str(DOCS))


async def small_and_editor() -> None:
    app = OrccadApp([], selected="missions/arm_recovery.orc", speed=1.0, run_now=True)
    async with app.run_test(size=(80, 24)) as pilot:
        run = app.screen
        await _until(pilot, lambda: _logged(run, "TrackPID (site 2) starts"))
        await pilot.pause(1.0)
        await pilot.press("space")
        await pilot.pause(0.5)
        app.save_screenshot("tui-run-80x24.svg", str(DOCS))
        await pilot.press("a")
        await _until(pilot, lambda: _report_shown(app))
    app = OrccadApp(["missions/false_property.orc"], selected="missions/false_property.orc")
    async with app.run_test(size=SIZE) as pilot:
        await pilot.press("ctrl+e")
        editor = app.screen
        area = editor.query_one("#editor")
        area.move_cursor((26, 0))
        area.insert("    run Plac();\n")
        await _until(pilot, lambda: bool(editor.diagnostics))
        await pilot.pause(0.5)
        app.save_screenshot("tui-editor.svg", str(DOCS))


async def replay() -> None:
    app = OrccadApp(["missions/false_property.orc"], selected="missions/false_property.orc")
    async with app.run_test(size=SIZE) as pilot:
        await pilot.press("c")
        await _until(pilot, lambda: getattr(app.screen, "report", None) is not None)
        await pilot.press("enter", "right", "right")  # placed_after_approach, instant 3
        await pilot.pause(0.5)
        app.clear_notifications()
        await pilot.pause(0.2)
        app.save_screenshot("tui-replay.svg", str(DOCS))


async def campaign() -> None:
    from orccad_app.tui.screens.campaign import CampaignScreen

    with tempfile.TemporaryDirectory() as folder:
        db = str(Path(folder) / "auv_survey.campaign.db")
        app = OrccadApp([], selected="missions/auv_survey.orc",
                        campaign={"db": db, "runs": 16, "workers": 2})
        async with app.run_test(size=SIZE) as pilot:
            await _until(pilot, lambda: isinstance(app.screen, CampaignScreen))
            screen = app.screen
            await pilot.press("s")
            await _until(pilot, lambda: screen.state == "finished" and screen.snapshot
                         is not None and screen.snapshot.runs == 16, timeout=600)
            await pilot.pause(0.5)
            app.clear_notifications()
            screen.query_one("#campaign-db").value = "auv_survey.campaign.db"
            status = screen.query_one("#campaign-status")
            status.update(str(status.content).replace(db, "auv_survey.campaign.db"))
            await pilot.pause(0.2)
            app.save_screenshot("tui-campaign.svg", str(DOCS))


def main() -> None:
    if sys.argv[1:] == ["campaign"]:
        asyncio.run(campaign())
        return
    asyncio.run(campaign())
    asyncio.run(replay())
    asyncio.run(small_and_editor())
    asyncio.run(browser())
    asyncio.run(arm_run())
    if Path("missions/auv_survey.orc").exists():
        asyncio.run(auv_run())
    print("\n".join(str(p) for p in sorted(DOCS.glob("tui-*.svg"))))


if __name__ == "__main__":
    main()
