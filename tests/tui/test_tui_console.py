"""Pilots of the mission console's features (issue 18): where the mission is, truthful
status, plots, inputs (typed values, pulse and hold), help and command palette, search and
preview in the browser, the editor with live diagnostics, the safe export."""

from __future__ import annotations

import os
import shutil
from pathlib import Path

from orccad_app.tui.app import OrccadApp
from orccad_app.tui.commands import commands_for
from orccad_app.tui.messages import InputRequested
from orccad_app.tui.screens.browser import BrowserScreen
from orccad_app.tui.screens.editor import EditorScreen
from orccad_app.tui.screens.help import HelpScreen
from orccad_app.tui.screens.run import RunScreen
from orccad_app.tui.session import LiveSession, parse_value
from orccad_app.tui.status import SpeedMeter
from orccad_app.tui.live import LiveUpdate

from tests.tui.test_tui_app import _report_shown, _text, _until, pilot_test

RECOVERY = "missions/arm_recovery.orc"
SIZE = (160, 48)


def _line_of(text: str, path: str = RECOVERY) -> int:
    return next(n for n, line in enumerate(Path(path).read_text().splitlines(), 1)
                if text in line)


async def _paused_run(pilot, app) -> RunScreen:
    await pilot.pause()
    run = app.screen
    assert isinstance(run, RunScreen)
    await _until(pilot, lambda: run.last is not None)
    return run


@pilot_test
async def test_paused_run_shows_where_the_mission_waits_and_its_rta():
    app = OrccadApp([], selected=RECOVERY, speed=0, run_now=True)
    async with app.run_test(size=SIZE) as pilot:
        run = await _paused_run(pilot, app)
        status = _text(run, "#run-status")
        homing = _line_of("run mission Homing;")
        assert "PAUSED" in status and "speed paused" in status
        # Home's measurement pre-condition (homing.orc:26, the sub-mission Homing imported
        # from lib/homing.orc), reached through 'run mission Homing' (arm_recovery.orc:37)
        assert f"waiting at arm_recovery.orc:{homing}, homing.orc:26" in status
        assert "running Home at homing.orc:9" in status
        assert "of 60 s" in status  # progress against the horizon
        await pilot.press("o")
        assert run.query_one("#run-tabs").active == "source-tab"
        source = run.query_one("#run-source")
        assert source.waiting == [homing] and source.sites == []
        assert "in homing.orc:26" in _text(run, "#run-source")
        await pilot.press("e")
        rta = _text(run, "#rta-text")
        assert "Home[/b] (site 0): phase 2" in rta and "▶ 2 measuring" in rta
        await pilot.press("t")
        table = run.query_one("#tcs")
        rows = [table.get_row_at(i) for i in range(table.row_count)]
        assert rows[0][0].startswith("Home") and rows[0][5] == "yes"
        assert any(row[0] == "cpu0 load" for row in rows), rows
        await pilot.press("a")
        await _until(pilot, lambda: _report_shown(app))


def test_the_actual_speed_excludes_pauses_and_a_slow_run_is_flagged():
    meter = SpeedMeter()
    meter.add(LiveUpdate(0, 0, "running", "1×", wall_s=10.0, paused_s=0.0))
    meter.add(LiveUpdate(1_000_000_000, 0, "running", "1×", wall_s=13.0, paused_s=2.0))
    assert meter.actual == 1.0  # 1 s simulated in 3 s of wall time, 2 of them paused
    meter.add(LiveUpdate(1_500_000_000, 0, "running", "1×", wall_s=14.0, paused_s=2.0))
    assert meter.actual == 0.5  # over the last 2 s of updates: 0.5 s simulated in 1 s

    class _Session:  # what status_text reads
        mission, path = "M", "m.orc"

        class pace:  # noqa: N801 - a stand-in attribute holder
            factor, paused, label, paused_s = 1.0, False, "1×", 0.0

        class automaton:  # noqa: N801
            waiting, labels = ((),), ()

        class run:  # noqa: N801
            until_ns = 60_000_000_000

    from orccad_app.tui.status import status_text
    text = status_text(_Session, LiveUpdate(1_500_000_000, 0, "running", "1×"), meter)
    assert "speed 1× (actual 0.50×)" in text and "lagging: 0.50× of the 1× asked" in text


def test_the_report_ratio_excludes_pauses():
    session = LiveSession("missions/arm_pid.orc", None, lambda update: None, speed=None)
    session.pace._paused_s = 0.25  # as if paused a quarter of a second
    session.execute()
    report = session.report()
    assert "  paused 0.25 s of wall time, not counted above" in report.splitlines()[2]


def test_typed_values_are_parsed_or_refused():
    assert parse_value("3", "int") == 3 and parse_value("0.8", "float") == 0.8
    assert parse_value("true", "bool") is True and parse_value("[1, 2.5]", "vector") == (1.0, 2.5)
    for text, type_name in (("abc", "float"), ("", "float"), ("0.5", "int"), ("maybe", "bool"),
                            ("1, 2", "vector"), ("nan", "float")):
        try:
            parse_value(text, type_name)
        except ValueError as error:
            assert f"is not a {type_name} value" in str(error)
        else:
            raise AssertionError(f"{text!r} accepted as {type_name}")


@pilot_test
async def test_a_valued_input_is_validated_and_a_held_input_sustained():
    app = OrccadApp([], selected=RECOVERY, speed=0, run_now=True)
    requested = []
    async with app.run_test(size=SIZE, message_hook=lambda m: isinstance(
            m, InputRequested) and requested.append(m)) as pilot:
        run = await _paused_run(pilot, app)
        run.query_one("#input-value").value = "lots"
        await pilot.press("3")  # Gripper: float
        assert not requested  # refused, not sent as 1.0
        assert any("'lots' is not a float value" in n.message for n in app._notifications)
        run.query_one("#input-value").value = "0.8"
        await pilot.press("3")
        unique = list({id(m): m for m in requested}.values())
        assert [(m.name, m.value, m.hold) for m in unique] == [("Gripper", 0.8, False)]
        await pilot.press("h")  # hold mode
        await pilot.press("2")  # Hold, held at every instant
        assert run.session.observer.held == ("Hold",)
        assert run.query_one("#input-Hold").has_class("-held")
        await pilot.press("2")  # released
        assert run.session.observer.held == ()
        await pilot.press("a")
        await _until(pilot, lambda: _report_shown(app))


class _Inputs:
    """Records, for each reaction, its time and inputs; releases a held input at ``t_ns``."""

    def __init__(self, observer, name, t_ns):
        self.observer, self.name, self.t_ns = observer, name, t_ns
        self.seen = []

    def on_reaction(self, t_ns, inputs, outputs, status):
        if self.name in inputs:
            self.seen.append(t_ns)
        if t_ns >= self.t_ns and self.name in self.observer.held:
            self.observer.release(self.name)


def test_a_held_input_is_present_at_every_instant_until_released():
    """Gripper held from the start is an input of a reaction at every tick (1 ms) from its
    due instant (the second tick) until its release at 0.5 s, and never after; the report
    has one record for it."""
    session = LiveSession(RECOVERY, None, lambda update: None, speed=None, until_s=1.0)
    session.observer.hold("Gripper", 0.9)
    probe = _Inputs(session.observer, "Gripper", 500_000_000)
    session.run.add_observer(probe)
    session.execute()
    ticks = sorted(set(probe.seen))
    assert ticks[0] == 2_000_000 and 500_000_000 <= ticks[-1] <= 503_000_000
    assert ticks == list(range(ticks[0], ticks[-1] + 1, 1_000_000))  # every tick, no other
    [record] = session.observer.injected
    assert (record.by, record.time_ns, record.until_ns) == ("user (held)", ticks[0], ticks[-1])
    assert record.instants == len(ticks)


@pilot_test
async def test_plots_have_series_setpoints_markers_window_and_chooser():
    app = OrccadApp([], selected=RECOVERY, speed=None, run_now=True)
    async with app.run_test(size=SIZE) as pilot:
        await _until(pilot, lambda: _report_shown(app), timeout=60)
        await pilot.press("escape")
        run = app.screen  # the run (in its own process) may end before the first pause
        assert isinstance(run, RunScreen)
        plots = run.query_one("#plots")
        assert {"arm.q[0]", "qd[0]", "tracking error"} <= set(plots.series)
        assert plots.shown == ["arm.q[0]", "arm.q[1]", "arm.q[2]"]  # each over its qd[i]
        kinds = {m.kind for m in plots.markers}
        assert "task" in kinds
        assert min(m.t_s for m in plots.markers if m.kind == "task") == 0.0
        await pilot.press("w")
        assert plots.rolling
        await pilot.press("p")
        chooser = app.screen
        chooser.query_one("#series-list").deselect_all()
        chooser.query_one("#series-list").select("tracking error")
        await pilot.click("#series-ok")
        assert plots.shown == ["tracking error"]
        assert "tracking error" in _text(run, "#plots-caption")


@pilot_test
async def test_help_lists_the_keys_of_the_current_screen():
    app = OrccadApp([RECOVERY], selected=RECOVERY)
    async with app.run_test(size=SIZE) as pilot:
        await pilot.press("question_mark")
        assert isinstance(app.screen, HelpScreen)
        text = _text(app.screen, "#help-text")
        assert "run the selected mission live" in text and "ctrl+e" in text
        await pilot.press("escape")
        assert isinstance(app.screen, BrowserScreen)
        await pilot.press("f1")
        assert isinstance(app.screen, HelpScreen)


@pilot_test
async def test_the_command_palette_offers_the_app_commands():
    app = OrccadApp([], selected="missions/auv_survey.orc", speed=0, run_now=True)
    async with app.run_test(size=SIZE) as pilot:
        run = await _paused_run(pilot, app)
        titles = {title: callback for title, callback, _ in commands_for(app, run)}
        assert {"Inject fault auv.leak", "Speed: 10×", "Open mission missions/arm_pid.orc",
                "Help: the keys of this screen"} <= set(titles)
        run.query_one("#input-value").value = "1"
        titles["Inject fault auv.leak"]()
        titles["Speed: 10×"]()
        assert run.session.pace.label == "10×"
        await _until(pilot, lambda: any(r.name == "auv.leak" for r in
                                        run.session.observer.injected), timeout=60)
        await pilot.press("a")
        await _until(pilot, lambda: _report_shown(app), timeout=60)


@pilot_test
async def test_browser_search_preview_and_empty_state(tmp_path, monkeypatch):
    app = OrccadApp([RECOVERY], selected=RECOVERY)
    async with app.run_test(size=SIZE) as pilot:
        screen = app.screen
        await pilot.press("slash")
        await pilot.press(*"auv_s")
        await pilot.pause()
        names = [item.name for item in screen.query("#files ListItem")]
        assert names == ["missions/auv_survey.orc"]
        await pilot.press("enter")
        assert screen.selected == "missions/auv_survey.orc"
        screen.query_one("#files-search").value = ""
        await pilot.pause()
        files = screen.query_one("#files")
        files.focus()
        files.index = 0
        await pilot.press("down")  # the arrow keys preview
        await pilot.pause()
        assert screen.selected == files.highlighted_child.name
    monkeypatch.chdir(tmp_path)
    empty = OrccadApp([])
    async with empty.run_test(size=(80, 24)) as pilot:
        assert "No mission here" in _text(empty.screen, "#source-view")


@pilot_test
async def test_the_editor_shows_live_diagnostics_jumps_saves_and_reloads(tmp_path):
    path = tmp_path / "pid.orc"
    shutil.copy("missions/arm_pid.orc", path)
    app = OrccadApp([str(path)], selected=str(path))
    async with app.run_test(size=SIZE) as pilot:
        await pilot.press("ctrl+e")
        editor = app.screen
        assert isinstance(editor, EditorScreen)
        area = editor.query_one("#editor")
        await _until(pilot, lambda: editor.diagnostics == [] and
                     editor.query_one("#diagnostics").option_count == 1)
        area.move_cursor((7, 0))  # line 8: robottask TrackPID …
        area.insert("    oops;\n")
        await _until(pilot, lambda: any(d.severity == "error" for d in editor.diagnostics))
        assert 8 in area.error_lines
        area.move_cursor((0, 0))
        editor.query_one("#diagnostics").highlighted = 0
        editor.jump_to(0)
        assert area.cursor_location[0] == editor.diagnostics[0].line - 1
        await pilot.press("ctrl+s")
        assert "oops;" in path.read_text()
        assert not list(tmp_path.glob(".*.part"))
        path.write_text(Path("missions/arm_pid.orc").read_text() + "// changed on disk\n")
        await _until(pilot, lambda: "changed on disk" in area.text, timeout=10)


@pilot_test
async def test_export_asks_before_overwriting_and_writes_atomically(tmp_path):
    app = OrccadApp([], selected="missions/arm_pid.orc", speed=None, run_now=True)
    async with app.run_test(size=SIZE) as pilot:
        await _until(pilot, lambda: _report_shown(app), timeout=60)
        report = app.screen
        target = tmp_path / "run.csv"
        target.write_text("precious")
        report.query_one("#export-path").value = str(target)
        await pilot.press("e")
        await pilot.pause(0.3)
        assert target.read_text() == "precious"  # not overwritten silently
        assert any("exists: press e again" in n.message for n in app._notifications)
        await pilot.press("e")
        await _until(pilot, lambda: not report.exporting and target.read_text() != "precious")
        assert target.read_text().startswith("time_ns,event,module,port,job,value")
        assert sorted(p.name for p in tmp_path.iterdir()) == ["run.csv"]  # no partial file


def _hostile_files(folder: Path) -> dict[str, tuple[Path, str]]:
    """Files the console is given: name -> (path, the located message it shows)."""
    binary = folder / "binary.orc"
    binary.write_bytes(b"mission M {\x89PNG\r\n\x1a\n\x00\x00\xff garbage")
    latin = folder / "latin.orc"
    latin.write_bytes("mission M { output Ö; emit Ö; }\n".encode("latin-1"))
    nul = folder / "nul.orc"
    nul.write_bytes(b"mission M {\n  output O;\x00 emit O; }\n")
    fifo = folder / "fifo.orc"
    os.mkfifo(fifo)
    importer = folder / "imports_a_fifo.orc"
    importer.write_text('from "fifo.orc" import X;\nmission M { run mission X; }\n')
    return {"binary": (binary, "1:12: error: not UTF-8 text: byte 0x89 cannot be decoded"),
            "latin-1": (latin, "1:20: error: not UTF-8 text: byte 0xd6 cannot be decoded"),
            "NUL": (nul, "2:12: error: a binary file (it holds a NUL byte)"),
            "a FIFO": (fifo, f"error: {fifo}: a FIFO, not a regular file"),
            "an import of a FIFO": (importer, f'1:6: error: cannot import "fifo.orc": {fifo}: '
                                              "a FIFO, not a regular file")}


@pilot_test
async def test_a_binary_file_or_an_import_of_a_fifo_is_one_located_message(tmp_path):
    """Issue 34 item 13: on main, ctrl+e on a binary or Latin-1 file ended the console with
    Textual's crash report of a UnicodeDecodeError, on a FIFO it hung the console, and the
    browser said 'not UTF-8 text' without the place."""
    hostile = _hostile_files(tmp_path)
    app = OrccadApp([str(tmp_path)], selected=str(hostile["binary"][0]))
    async with app.run_test(size=SIZE) as pilot:
        browser = app.screen
        assert isinstance(browser, BrowserScreen)
        for name, (path, said) in hostile.items():
            browser.open(str(path))
            await pilot.pause()
            summary = browser.query_one("#summary-text").text
            assert summary.startswith(said), (name, summary)
            assert "codec" not in summary and "Traceback" not in summary
            if name == "an import of a FIFO":
                continue  # a file that reads: the editor opens, its diagnostics say it
            app.clear_notifications()
            await pilot.press("ctrl+e")
            await pilot.pause()
            assert app.screen is browser, name  # the editor did not open
            messages = [n.message for n in app._notifications]
            assert len(messages) == 1 and messages[0].startswith("cannot edit "), messages
            assert said.removeprefix("error: ").split(": error: ")[-1] in messages[0]
            assert "\n" not in messages[0] and "codec" not in messages[0]
    assert app.return_code in (None, 0)  # no crash report
