"""The run screen: a live mission run — where the mission is (the statements it waits at, the
running Robot-Tasks and their RTA phase), plots, the TCS's load, the log and the inputs."""

from __future__ import annotations

import math

from textual import on, work
from textual.app import ComposeResult
from textual.binding import Binding
from textual.containers import Container, Horizontal, Vertical, VerticalScroll
from textual.screen import Screen
from textual.widgets import Footer, Header, Static, TabbedContent, TabPane

from orccad_app.diagnostics import OrccadError
from orccad_app.tui.live import LiveUpdate, LogEntry
from orccad_app.tui.messages import InputRequested, RunFailed, RunFinished, RunUpdated
from orccad_app.tui.screens.series import SeriesScreen
from orccad_app.tui.session import LiveSession
from orccad_app.tui.status import (SpeedMeter, rta_text, run_site_lines, status_text,
                                    tasks_in_state, tcs_rows, waiting_elsewhere,
                                    waiting_lines)
from orccad_app.tui.widgets.event_log import EventLog
from orccad_app.tui.widgets.inputs import InputBar
from orccad_app.tui.widgets.plots import BUSY_PLOT_FRAMES, REDRAW_S, Marker, Plots
from orccad_app.tui.widgets.source_view import SourceView
from orccad_app.tui.widgets.tables import LoadTable, TaskTable, TcsTable
from orccad_app.tui.screens import orccad

__all__ = ["RunScreen", "SPEEDS"]

SPEEDS = {"pause": 0.0, "realtime": 1.0, "fast": 10.0, "max": None}
"""Speed actions -> pacing factor (``None``: as fast as possible)."""

_MARKED = {"exception": "exception", "input": "input", "fault": "fault"}


class RunScreen(Screen):
    """Runs ``session`` in a worker thread and shows what its observer reports."""

    AUTO_FOCUS = "#plots"

    BINDINGS = [
        Binding("space", "toggle_pause", "Pause/resume"),
        Binding("r", "speed('realtime')", "1×", show=False, tooltip="real time (1×)"),
        Binding("x", "speed('fast')", "10×", show=False, tooltip="10× real time"),
        Binding("m", "speed('max')", "Max", show=False, tooltip="as fast as possible"),
        Binding("i", "inject", "Inject", tooltip="inject the fault or event chosen in the list"),
        Binding("h", "hold_mode", "Pulse/hold", tooltip="inputs: pulse (one instant) or hold "
                                                        "(every instant until pressed again)"),
        Binding("g", "tab('plots-tab')", "Plots", show=False, tooltip="show the plots"),
        Binding("o", "tab('source-tab')", "Source", show=False,
                tooltip="show the source with the statements the mission waits at"),
        Binding("e", "tab('rta-tab')", "RTA", show=False,
                tooltip="show the running Robot-Tasks' RTA phases"),
        Binding("t", "tab('tcs-tab')", "TCS", show=False,
                tooltip="show the TCS: modules, processors, load, misses"),
        Binding("p", "choose_series", "Series", show=False, tooltip="choose the plotted series"),
        Binding("w", "window", "Window", show=False,
                tooltip="plots: whole mission or the last 10 s"),
        Binding("a", "abort", "Abort"),
        Binding("v", "report", "Report", show=False, tooltip="the report (once the run is over)"),
        Binding("escape", "back", "Back", tooltip="back to the browser (once the run is over)"),
        *[Binding(str(n), f"raise_input({n})", f"input {n}", show=False,
                  tooltip=f"raise (or hold/release) input {n} of the bar") for n in range(1, 10)],
    ]

    def __init__(self, session: LiveSession) -> None:
        super().__init__()
        self.session = session
        self.finished = False
        self.report_text = ""
        self._resume_speed: float | None = session.pace.factor or 1.0
        self.meter = SpeedMeter()
        self.last: LiveUpdate | None = None
        self._tasks: list[tuple[str, int, int]] = []
        self._busy_frames = 0  # frames taken at max speed (the plots redraw every few)

    def compose(self) -> ComposeResult:
        yield Header()
        yield Static(id="run-status")
        with Horizontal(id="run-body"):
            with Vertical(id="run-left"):
                yield TaskTable(id="tasks")
                yield LoadTable(id="load")
            with Container(id="run-main"):
                with TabbedContent(id="run-tabs"):
                    with TabPane("Plots", id="plots-tab"):
                        yield Plots(id="plots")
                    with TabPane("Source", id="source-tab"):
                        with VerticalScroll():
                            yield SourceView(id="run-source")
                    with TabPane("RTA", id="rta-tab"):
                        with VerticalScroll():
                            yield Static(id="rta-text")
                    with TabPane("TCS", id="tcs-tab"):
                        yield TcsTable(id="tcs")
                yield EventLog(id="log")
        yield InputBar(self.session.inputs, self.session.events, self.session.faults,
                       id="inputs")
        yield Footer(compact=True)

    def on_mount(self) -> None:
        self.query_one(EventLog).border_title = "log"
        self.title = f"ORCCAD — run {self.session.mission}"
        self.sub_title = self.session.path
        if self.session.script is not None:
            self.sub_title += f" — inputs of the {self.session.script.by}"
        self.query_one(TaskTable).show([])
        self._where(None)
        self._status(None)
        self._execute()

    @work(thread=True, exclusive=True, group="run")
    def _execute(self) -> None:
        try:
            result = self.session.execute()
        except Exception as error:  # shown to the user; the UI stays up
            self.post_message(RunFailed(f"the run failed: {error}"))
            return
        self.post_message(RunFinished(result, self.session.report()))

    def _status(self, update: LiveUpdate | None) -> None:
        limit = 4 if self.size.width < 120 else 12  # where it waits: what fits on a line
        self.query_one("#run-status", Static).update(status_text(
            self.session, update, self.meter, limit), layout=False)  # two lines, always

    def _where(self, update: LiveUpdate | None) -> None:
        """The source with the statements the mission waits at, the RTA and TCS tabs."""
        state = None if update is None else update.state
        tasks = tasks_in_state(self.session, state)
        self.query_one("#run-source", SourceView).show_run(
            self.session.path, self.session.text, waiting_lines(self.session, state),
            run_site_lines(self.session, state), waiting_elsewhere(self.session, state))
        self.query_one("#rta-text", Static).update(rta_text(self.session, tasks))
        loads = {} if update is None else update.loads
        misses = {} if update is None else update.misses
        self.query_one(TcsTable).show(tcs_rows(self.session, tasks, loads, misses))

    @on(RunUpdated)
    def _updated(self, message: RunUpdated) -> None:
        try:
            self._show(message.update)
        finally:
            self.session.observer.frame_taken()  # the run may post the next frame

    def _show(self, update: LiveUpdate) -> None:
        self.last = update
        self.meter.add(update)
        if not self.finished:
            self._status(update)
        if update.state != getattr(self, "_shown_state", -1) or update.tasks != self._tasks:
            self._shown_state, self._tasks = update.state, update.tasks
            self._where(update)
        self.query_one(TaskTable).show(update.tasks or tasks_in_state(self.session,
                                                                      update.state))
        self.query_one(LoadTable).show(update.loads, update.misses)
        plots = self.query_one(Plots)
        plots.add_samples(update.samples)
        plots.add_markers(_markers(update.log))
        if self.session.pace.factor is None:  # max speed: the plots follow the frames
            plots.min_interval_s = math.inf
            self._busy_frames += 1
            if self._busy_frames % BUSY_PLOT_FRAMES == 0:
                plots.redraw()
        else:
            plots.min_interval_s = REDRAW_S
        self.query_one(EventLog).add(update.log)

    @on(RunFinished)
    def _finished(self, message: RunFinished) -> None:
        self.finished = True
        self.report_text = message.report
        self.query_one(Plots).redraw()  # the whole run, at once
        result = message.result
        reason = f": {result.reason}" if result.reason else ""
        self.query_one(EventLog).add([LogEntry(result.sim_time_ns, "status",
                                               f"mission {result.status}{reason}")])
        self.query_one("#run-status", Static).update(
            f"mission {result.mission} {result.status}{reason} — simulated "
            f"{result.sim_time_ns / 1e9:.3f} s in {result.wall_time_s:.2f} s wall "
            f"({self.session.pace.paused_s:.1f} s paused)\npress v for the report, "
            f"esc for the browser")
        orccad(self).show_report(self.session, message.report)

    @on(RunFailed)
    def _failed(self, message: RunFailed) -> None:
        self.finished = True
        self.query_one("#run-status", Static).update(message.message)
        self.notify(message.message, severity="error", timeout=10)

    @on(InputRequested)
    def _input(self, message: InputRequested) -> None:
        message.stop()
        if self.finished:
            self.notify("the run is over", severity="warning")
            return
        observer = self.session.observer
        shown = message.name if message.value is None else f"{message.name}({message.value})"
        if message.fault:
            try:
                observer.inject_fault(message.name, message.value)
            except OrccadError as error:
                self.notify(f"fault {message.name}: {error.message}", severity="error")
                return
            self.notify(f"fault {message.name}={message.value} injected")
        elif message.release:
            observer.release(message.name)
            self.notify(f"{message.name} released")
        elif message.hold:
            observer.hold(message.name, message.value)
            self.notify(f"{shown} held at every instant (press its key again to release)")
        else:
            observer.raise_input(message.name, message.value)
            self.notify(f"{shown} raised")

    def action_raise_input(self, number: int) -> None:
        self.query_one(InputBar).request(number)

    def action_inject(self) -> None:
        self.query_one(InputBar).inject()

    def raise_named(self, name: str) -> None:
        """Raise input ``name``, or inject event or fault ``name`` (the command palette)."""
        bar = self.query_one(InputBar)
        signal = next((s for s in bar.inputs if s.name == name), None)
        if signal is not None:
            bar.request(bar.keyed.index(name) + 1) if name in bar.keyed else bar._raise(signal)
        else:
            bar.inject(name)

    def action_hold_mode(self) -> None:
        bar = self.query_one(InputBar)
        bar.cycle_mode()
        self.notify(f"inputs: {bar.mode}")

    def action_tab(self, tab: str) -> None:
        self.query_one("#run-tabs", TabbedContent).active = tab

    def action_choose_series(self) -> None:
        plots = self.query_one(Plots)
        if not plots.series:
            self.notify("no samples yet", severity="warning")
            return

        def chosen(names: list[str] | None) -> None:
            if names is not None:
                plots.choose(names)

        self.action_tab("plots-tab")
        self.app.push_screen(SeriesScreen(plots.series, plots.shown), chosen)

    def action_window(self) -> None:
        plots = self.query_one(Plots)
        plots.toggle_window()
        self.notify("plots: " + ("the last 10 s" if plots.rolling else "the whole mission"))

    def action_speed(self, name: str) -> None:
        self.session.pace.set(SPEEDS[name])
        if SPEEDS[name] != 0:
            self._resume_speed = SPEEDS[name]
        self.meter.reset()
        self._status(self.last)
        self.notify(f"speed {self.session.pace.label}")

    def action_toggle_pause(self) -> None:
        if self.session.pace.factor == 0:
            self.session.pace.set(self._resume_speed)
            self.meter.reset()
            self._status(self.last)
        else:
            self.action_speed("pause")

    def action_abort(self) -> None:
        if not self.finished:
            self.session.observer.abort()

    def action_report(self) -> None:
        if self.finished and self.report_text:
            orccad(self).show_report(self.session, self.report_text)

    def action_back(self) -> None:
        if not self.finished:
            self.notify("the run is still going: press a to abort it first")
            return
        self.app.pop_screen()

    def on_unmount(self) -> None:
        if not self.finished:
            self.session.observer.abort("the run screen was closed")


def _markers(log: list[LogEntry]) -> list[Marker]:
    found = []
    for entry in log:
        kind = _MARKED.get(entry.kind)
        if entry.task_start:
            kind = "task"
        if kind is not None:
            found.append(Marker(entry.time_ns / 1e9, kind, entry.text))
    return found
