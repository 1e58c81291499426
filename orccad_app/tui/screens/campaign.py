"""The campaign screen: start a campaign (or a falsification) from a spec, or open a
database, and watch its answer form — progress, each outcome's probability with its interval,
the robustness histograms, the runs closest to violation; ``enter`` on a run replays it in the
live view with its setting (seed, injections, ``--set``/``--timing``).

The search runs as ``orccad campaign`` / ``orccad falsify`` in a child process
(:class:`~orccad_app.tui.campaigns.SearchProcess`): its worker pool never shares Textual's
event loop. The screen reads what it has recorded twice a second in a worker thread; closing
the screen stops it as Ctrl-C does, leaving the database resumable (``s`` resumes it).
"""

from __future__ import annotations

import os
from pathlib import Path

from textual import on, work
from textual.app import ComposeResult
from textual.binding import Binding
from textual.containers import Horizontal, VerticalScroll
from textual.message import Message
from textual.screen import Screen
from textual.widgets import Button, DataTable, Footer, Header, Input, Label, Static

from orccad_app.diagnostics import OrccadError
from orccad_app.pipeline import require_regular_file
from orccad_app.reactive.status import MissionStatus
from orccad_app.tui.campaigns import (Bin, CampaignSnapshot, Candidate, FalsifySnapshot,
                                      SearchProcess, default_db, read_campaign, read_study)
from orccad_app.tui.screens import orccad

__all__ = ["CampaignScreen", "MODES", "REFRESH_S"]

MODES = ("campaign", "falsify")
REFRESH_S = 0.5
"""How often the screen reads the database [s] (wall time)."""
_BAR = 24
"""Width of a histogram's longest bar [characters]."""


class _Read(Message):
    """A snapshot of the database (or why it could not be read)."""

    bubble = False

    def __init__(self, snapshot: CampaignSnapshot | FalsifySnapshot | None,
                 error: str | None = None) -> None:
        super().__init__()
        self.snapshot = snapshot
        self.error = error


class CampaignScreen(Screen):
    """See the module docstring. ``file``: the mission file; ``spec``: its campaign spec;
    ``db``: the database (default: the spec's name with ``.db``)."""

    AUTO_FOCUS = "#candidates"

    BINDINGS = [
        Binding("s", "start", "Start/resume",
                tooltip="start the campaign (or falsification), or resume the one in the "
                        "database"),
        Binding("x", "stop", "Stop", tooltip="stop it as Ctrl-C does: the database stays "
                                             "resumable"),
        Binding("o", "open", "Open db", tooltip="show the database in the field (no run)"),
        Binding("f", "mode", "Campaign/falsify",
                tooltip="switch between a campaign and a falsification"),
        Binding("enter", "replay", "Replay run", show=False,
                tooltip="replay the selected run in the live view"),
        Binding("escape", "back", "Back", tooltip="back (a running search is stopped, "
                                                  "resumable)"),
    ]

    def __init__(self, file: str | None, spec: str | None, db: str | None = None, *,
                 runs: int | None = None, workers: int | None = None,
                 mode: str = "campaign", prop: str = "", budget: int = 30) -> None:
        super().__init__()
        self.file = file
        self.spec = spec or ""
        self.db = db or (default_db(spec) if spec else "")
        self.runs, self.pool_workers = runs, workers
        self.mode = mode
        self.prop, self.budget = prop, budget
        self.process: SearchProcess | None = None
        self.snapshot: CampaignSnapshot | FalsifySnapshot | None = None
        self.state = "idle"
        """``idle``, ``running``, ``finished``, ``interrupted`` (resumable) or ``failed``."""
        self.candidates: list[Candidate] = []
        self._until_s: float | None = None
        self._reading = False
        self._last_read = False

    def compose(self) -> ComposeResult:
        yield Header()
        yield Static(id="campaign-status")
        with Horizontal(id="campaign-form"):
            yield Label("spec")
            yield Input(self.spec, id="campaign-spec", compact=True)
            yield Label("db")
            yield Input(self.db, id="campaign-db", compact=True)
            yield Label("runs", id="campaign-count-label")
            yield Input("" if self.runs is None else str(self.runs), id="campaign-count",
                        placeholder="spec's", compact=True, type="integer")
            yield Label("property", id="campaign-prop-label")
            yield Input(self.prop, id="campaign-prop", compact=True)
            yield Button("s start", id="campaign-start", compact=True, variant="primary")
        with Horizontal(id="campaign-body"):
            yield DataTable(id="estimates", cursor_type="none")
            with VerticalScroll(id="campaign-histogram-box"):
                yield Static(id="campaign-histogram")
        yield DataTable(id="candidates", cursor_type="row")
        yield Footer(compact=True)

    def on_mount(self) -> None:
        self.title = "ORCCAD — campaign"
        self.sub_title = self.file or ""
        self.query_one("#estimates", DataTable).add_columns("event", "count", "P",
                                                            "interval")
        self.query_one("#candidates", DataTable).add_columns(
            "run", "closest to violation of", "robustness", "outcome", "injections")
        self.query_one("#campaign-histogram-box").border_title = "robustness"
        self.query_one("#estimates").border_title = "outcome probabilities"
        self.query_one("#candidates").border_title = "runs to replay (enter)"
        self._show_mode()
        self._status()
        if self.db and os.path.lexists(self.db):
            self.action_open()
        self.set_interval(REFRESH_S, self._tick)

    # -- the form ------------------------------------------------------------------------

    def _field(self, name: str) -> str:
        return self.query_one(f"#campaign-{name}", Input).value.strip()

    def _show_mode(self) -> None:
        falsify = self.mode == "falsify"
        self.query_one("#campaign-count-label", Label).update("budget" if falsify else "runs")
        count = self.query_one("#campaign-count", Input)
        count.placeholder = "30" if falsify else "spec's"
        for name in ("#campaign-prop-label", "#campaign-prop"):
            self.query_one(name).display = falsify
        self.query_one("#estimates").display = not falsify
        self.query_one("#campaign-histogram-box").border_title = (
            "robustness of the trials" if falsify else "robustness")
        self.title = "ORCCAD — " + ("falsification" if falsify else "campaign")

    def action_mode(self) -> None:
        if self.process is not None and self.process.running:
            self.notify("a search is running: stop it (x) first", severity="warning")
            return
        self.mode = MODES[(MODES.index(self.mode) + 1) % len(MODES)]
        self.snapshot, self.state = None, "idle"
        if self.mode == "falsify" and self._field("db").endswith(".db") and \
                not self._field("db").endswith(".study.db"):
            self.query_one("#campaign-db", Input).value = \
                self._field("db")[:-3] + ".study.db"
        self._show_mode()
        self._show(None)

    def _count(self) -> int | None:
        text = self._field("count")
        if not text:
            return None
        value = int(text)
        if value < 1:
            raise ValueError(f"{'budget' if self.mode == 'falsify' else 'runs'} must be "
                             f">= 1, got {value}")
        return value

    # -- starting, stopping --------------------------------------------------------------

    def action_start(self) -> None:
        if self.process is not None and self.process.running:
            self.notify("the search is running", severity="warning")
            return
        if not self.file:
            self.notify("no mission file: open the campaign screen from a mission",
                        severity="error")
            return
        spec, db = self._field("spec"), self._field("db")
        if not spec:
            self.notify("type the campaign spec's path", severity="error")
            return
        try:
            require_regular_file(spec)  # missing, a folder, a FIFO: said as such
        except OrccadError as error:
            self.notify(f"spec: {error.message}", severity="error")
            return
        if not db:
            self.notify("type the database's path", severity="error")
            return
        try:
            count = self._count()
        except ValueError as error:
            self.notify(str(error), severity="error")
            return
        resume = Path(db).is_file() and Path(db).stat().st_size > 0
        if self.mode == "falsify":
            prop = self._field("prop")
            if not prop:
                self.notify("type the property to falsify", severity="error")
                return
            self.budget = count or self.budget
            self.prop = prop
            self.process = SearchProcess.falsify(self.file, spec, prop, db, budget=self.budget,
                                                 workers=self.pool_workers, resume=resume)
        else:
            self.runs = count
            self.process = SearchProcess.campaign(self.file, spec, db, runs=count,
                                                  workers=self.pool_workers, resume=resume)
        self.spec, self.db, self.state = spec, db, "running"
        self.notify(f"{'resuming' if resume else 'starting'} the {self.mode}: "
                    f"orccad {' '.join(self.process.args)}")
        self._status()

    @on(Button.Pressed, "#campaign-start")
    def _start_pressed(self) -> None:
        self.action_start()

    def action_stop(self) -> None:
        if self.process is None or not self.process.running:
            self.notify("no search is running", severity="warning")
            return
        self.notify("stopping: the finished runs stay in the database (s resumes)")
        self._stop()

    @work(thread=True, exclusive=True, group="campaign-stop")
    def _stop(self) -> None:
        process = self.process
        if process is not None:
            process.stop()

    def action_open(self) -> None:
        """Read the database in the field now (nothing runs)."""
        self.db = self._field("db")
        if not self.db:
            self.notify("type the database's path", severity="error")
            return
        self._read()  # what is wrong with the file, if anything, is said by the read

    def action_back(self) -> None:
        self._close()
        self.app.pop_screen()

    def on_unmount(self) -> None:
        self._close()

    def _close(self) -> None:
        """Stop a running search, leaving its database resumable."""
        if self.process is not None and self.process.running:
            self.process.stop()
            self.state = "interrupted"

    # -- reading -------------------------------------------------------------------------

    def _tick(self) -> None:
        """At the screen's fixed rate: read the database while a search runs; once it has
        ended, read it a last time and say how it ended."""
        process = self.process
        if process is None:
            return
        if self.state == "running":
            code = process.returncode
            if code is not None:
                self.state = {0: "finished", 1: "finished",
                              130: "interrupted"}.get(code, "failed")
                self._last_read = True  # a read that starts after the end sees every run
                if self.state == "failed":
                    self.notify(process.error_text() or f"the {self.mode} ended with status "
                                f"{code}", severity="error", timeout=15)
            self._status()
            self._read()
        elif self._last_read and not self._reading:
            self._last_read = False
            self._read()

    def _read(self) -> None:
        if not self._reading:
            self._reading = True
            self._load(self.mode, self._field("db"), self._field("spec"))

    @work(thread=True, exclusive=True, group="campaign-read")
    def _load(self, mode: str, db: str, spec: str) -> None:
        snapshot: CampaignSnapshot | FalsifySnapshot
        try:
            if mode == "falsify":
                snapshot = read_study(db, spec, self.prop or self._field("prop"),
                                      self._horizon(spec), budget=self.budget)
            else:
                snapshot = read_campaign(db, limit=self.runs)
        except OrccadError as error:
            self.post_message(_Read(None, error.format()))
        except Exception as error:  # noqa: BLE001 - a database being written: try again
            self.post_message(_Read(None, f"cannot read {db}: {error}"))
        else:
            self.post_message(_Read(snapshot))

    def _horizon(self, spec: str) -> float:
        """The falsification's run horizon, as ``orccad falsify`` sets it [s]."""
        if self._until_s is None:
            from orccad_app.campaign.adapter import CompiledMission

            if self.file is None:
                raise OrccadError("the mission file is unknown")
            from orccad_app.campaign.spec import load_spec

            loaded = load_spec(spec)
            self._until_s = loaded.until_s or CompiledMission(
                self.file, loaded.mission).default_until_s()
        return self._until_s

    @on(_Read)
    def _read_done(self, message: _Read) -> None:
        self._reading = False
        if message.error is not None:
            if self.state != "running":
                self.notify(message.error, severity="error", timeout=10)
            return
        self.snapshot = message.snapshot
        if isinstance(message.snapshot, CampaignSnapshot) and not self.file:
            self.file = message.snapshot.file
            self.sub_title = self.file
        self._show(message.snapshot)
        self._status()

    # -- showing -------------------------------------------------------------------------

    def _status(self) -> None:
        self.query_one("#campaign-status", Static).update(status_text(
            self.mode, self.state, self.snapshot, self.file, self._field("db")))

    def _show(self, snapshot: CampaignSnapshot | FalsifySnapshot | None) -> None:
        estimates = self.query_one("#estimates", DataTable)
        estimates.clear()
        if isinstance(snapshot, CampaignSnapshot):
            for row in estimate_rows(snapshot):
                estimates.add_row(*row)
        histograms: dict[str, list[Bin]] = {}
        if isinstance(snapshot, CampaignSnapshot):
            histograms = snapshot.histograms
        elif isinstance(snapshot, FalsifySnapshot):
            histograms = {snapshot.prop: snapshot.histogram}
        self.query_one("#campaign-histogram", Static).update(histogram_text(histograms))
        table = self.query_one("#candidates", DataTable)
        cursor = table.cursor_row
        table.clear()
        self.candidates = [] if snapshot is None else list(snapshot.candidates)
        for candidate in self.candidates:
            table.add_row(*candidate_row(candidate))
        if self.candidates:
            table.move_cursor(row=min(max(cursor, 0), len(self.candidates) - 1))

    # -- replaying -----------------------------------------------------------------------

    @on(DataTable.RowSelected, "#candidates")
    def _selected(self, event: DataTable.RowSelected) -> None:
        self.action_replay()

    def action_replay(self) -> None:
        table = self.query_one("#candidates", DataTable)
        if not self.candidates or not 0 <= table.cursor_row < len(self.candidates):
            self.notify("no run to replay yet", severity="warning")
            return
        if not self.file:
            self.notify("the mission file is unknown", severity="error")
            return
        candidate = self.candidates[table.cursor_row]
        mission = self.snapshot.mission if isinstance(self.snapshot, CampaignSnapshot) \
            else None
        what = "trial" if self.mode == "falsify" else "campaign run"
        orccad(self).start_run(self.file, mission or None, setting=candidate.setting,
                           by=f"{what} {candidate.run}")


def status_text(mode: str, state: str, snapshot: CampaignSnapshot | FalsifySnapshot | None,
                file: str | None, db: str) -> str:
    """Two lines: what runs where and how far it is; what to do next."""
    hint = {"idle": "s starts (or resumes the database), o opens the database, f switches "
                    "campaign/falsification",
            "running": "x stops it (the database stays resumable); enter replays a run",
            "finished": "enter replays the selected run in the live view",
            "interrupted": "stopped: every finished run is in the database; s resumes",
            "failed": "the command failed (its message is shown); fix the spec and press s"
            }[state]
    if isinstance(snapshot, CampaignSnapshot):
        share = snapshot.runs / snapshot.limit if snapshot.limit else 0.0
        bar = "█" * round(share * 20) + "░" * (20 - round(share * 20))
        done = snapshot.estimates.get(MissionStatus.DONE)
        p = "" if not done or done["p"] is None else (
            f"   P(done) = {done['p']:.3f} [{done['low']:.3f}, {done['high']:.3f}]")
        crashed = f"   {snapshot.crashed} crashed" if snapshot.crashed else ""
        head = (f"campaign {snapshot.mission} of {snapshot.file} ({state}): "
                f"{snapshot.runs}/{snapshot.limit} runs {bar} {share:.0%}{p}{crashed}   "
                f"db {snapshot.db}")
    elif isinstance(snapshot, FalsifySnapshot):
        share = snapshot.trials / snapshot.budget if snapshot.budget else 0.0
        bar = "█" * round(share * 20) + "░" * (20 - round(share * 20))
        best = "-" if snapshot.best is None else f"{snapshot.best:.4g}"
        found = ("no violation yet" if snapshot.first_violation is None else
                 f"[b red]violated[/], first at trial {snapshot.first_violation}")
        head = (f"falsification of {snapshot.prop} ({state}): {snapshot.trials}/"
                f"{snapshot.budget} trials {bar} {share:.0%}   best robustness {best}, "
                f"{found}   study {snapshot.study}")
    else:
        head = f"{mode} of {file or '(no mission file)'} ({state})   db {db or '-'}"
    return f"{head}\n{hint}"


def estimate_rows(snapshot: CampaignSnapshot) -> list[tuple[str, str, str, str]]:
    """``(event, k/n, P, [low, high])`` of every estimate defined on some run."""
    rows = []
    level = f"{100 * snapshot.confidence:g} %"
    for name, e in snapshot.estimates.items():
        if not e["runs"]:
            continue
        p = "-" if e["p"] is None else f"{e['p']:.3f}"
        rows.append((name, f"{e['count']}/{e['runs']}", p,
                     f"[{e['low']:.3f}, {e['high']:.3f}] {level}"))
    return rows


def histogram_text(histograms: dict[str, list[Bin]]) -> str:
    """Each histogram as lines ``[low, high)  ███ n``; bins left of 0 (violations) in red."""
    if not any(histograms.values()):
        return "no robustness recorded yet (a property or [[check]] of the spec gives one)"
    blocks = []
    for name, bins in histograms.items():
        if not bins:
            continue
        top = max(b.count for b in bins) or 1
        lines = [f"[b]{name}[/b] ({sum(b.count for b in bins)} runs; left of 0: violated)"]
        for b in bins:
            bar = "█" * round(_BAR * b.count / top) if b.count else ""
            style = "red" if b.high <= 0 else "yellow" if b.low < 0 else "green"
            lines.append(f"  {b.low:>10.4g} … {b.high:<10.4g} [{style}]{bar}[/] {b.count}")
        blocks.append("\n".join(lines))
    return "\n\n".join(blocks)


def candidate_row(candidate: Candidate) -> tuple[str, str, str, str, str]:
    """``(run, property or outcome, robustness, outcome, injections)``."""
    robustness = "-" if candidate.robustness is None else f"{candidate.robustness:.4g}"
    injections = ", ".join(candidate.setting.injections) or "-"
    return (str(candidate.run), candidate.what, robustness, candidate.outcome, injections)
