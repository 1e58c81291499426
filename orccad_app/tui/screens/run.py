"""The run screen: a live mission run, its automaton, tasks, plots, log, load and inputs."""

from __future__ import annotations

from textual import on, work
from textual.app import ComposeResult
from textual.binding import Binding
from textual.containers import Horizontal, Vertical
from textual.screen import Screen
from textual.widgets import Footer, Header, Static

from orccad_app.tui.live import LiveUpdate, LogEntry
from orccad_app.tui.messages import InputRequested, RunFailed, RunFinished, RunUpdated
from orccad_app.tui.session import LiveSession
from orccad_app.tui.widgets.event_log import EventLog
from orccad_app.tui.widgets.inputs import InputBar
from orccad_app.tui.widgets.plots import Plots
from orccad_app.tui.widgets.tables import LoadTable, TaskTable

__all__ = ["RunScreen", "SPEEDS"]

SPEEDS = {"pause": 0.0, "realtime": 1.0, "fast": 10.0, "max": None}
"""Speed actions -> pacing factor (``None``: as fast as possible)."""


class RunScreen(Screen):
    """Runs ``session`` in a worker thread and shows what its observer reports."""

    AUTO_FOCUS = "#plots"

    BINDINGS = [
        Binding("space", "toggle_pause", "Pause/resume"),
        Binding("r", "speed('realtime')", "1×"),
        Binding("x", "speed('fast')", "10×"),
        Binding("m", "speed('max')", "Max"),
        Binding("i", "inject", "Inject"),
        Binding("a", "abort", "Abort"),
        Binding("v", "report", "Report", show=False),
        Binding("escape", "back", "Back"),
        *[Binding(str(n), f"raise_input({n})", f"input {n}", show=False) for n in range(1, 10)],
    ]

    def __init__(self, session: LiveSession) -> None:
        super().__init__()
        self.session = session
        self.finished = False
        self.report_text = ""
        self._resume_speed: float | None = session.pace.factor or 1.0

    def compose(self) -> ComposeResult:
        yield Header()
        with Horizontal(id="run-body"):
            with Vertical(id="run-left"):
                yield Static(id="run-status")
                yield TaskTable(id="tasks")
                yield LoadTable(id="load")
            yield Plots(id="plots")
            yield EventLog(id="log")
        yield InputBar(self.session.inputs, self.session.events, self.session.faults,
                       id="inputs")
        yield Footer()

    def on_mount(self) -> None:
        self.query_one(Plots).border_title = "plots"
        self.query_one(EventLog).border_title = "log"
        self.title = f"ORCCAD — run {self.session.mission}"
        self.sub_title = self.session.path
        self.query_one(TaskTable).show([])
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
        if update is None:
            text = f"mission {self.session.mission}\nstarting at {self.session.pace.label}…"
        else:
            text = (f"mission {self.session.mission}   t = {update.time_ns / 1e9:.3f} s\n"
                    f"speed {update.speed}   automaton state {update.state}   "
                    f"status {update.status}")
        self.query_one("#run-status", Static).update(text)

    @on(RunUpdated)
    def _updated(self, message: RunUpdated) -> None:
        update = message.update
        if not self.finished:
            self._status(update)
        self.query_one(TaskTable).show(update.tasks)
        self.query_one(LoadTable).show(update.loads, update.misses)
        self.query_one(Plots).add_samples(update.samples)
        self.query_one(EventLog).add(update.log)

    @on(RunFinished)
    def _finished(self, message: RunFinished) -> None:
        self.finished = True
        self.report_text = message.report
        result = message.result
        reason = f": {result.reason}" if result.reason else ""
        self.query_one(EventLog).add([LogEntry(result.sim_time_ns, "status",
                                               f"mission {result.status}{reason}")])
        self.query_one("#run-status", Static).update(
            f"mission {result.mission} {result.status}{reason}\n"
            f"simulated {result.sim_time_ns / 1e9:.3f} s in {result.wall_time_s:.2f} s wall")
        self.app.show_report(self.session, message.report)

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
        if message.fault:
            self.session.observer.inject_fault(message.name, message.value)
            self.notify(f"fault {message.name}={message.value} injected")
        else:
            self.session.observer.raise_input(message.name, message.value)
            self.notify(f"{message.name} raised")

    def action_raise_input(self, number: int) -> None:
        self.query_one(InputBar).request(number)

    def action_inject(self) -> None:
        self.query_one(InputBar).inject()

    def action_speed(self, name: str) -> None:
        self.session.pace.set(SPEEDS[name])
        if SPEEDS[name] != 0:
            self._resume_speed = SPEEDS[name]
        self.notify(f"speed {self.session.pace.label}")

    def action_toggle_pause(self) -> None:
        if self.session.pace.factor == 0:
            self.session.pace.set(self._resume_speed)
        else:
            self.action_speed("pause")

    def action_abort(self) -> None:
        if not self.finished:
            self.session.observer.abort()

    def action_report(self) -> None:
        if self.finished and self.report_text:
            self.app.show_report(self.session, self.report_text)

    def action_back(self) -> None:
        if not self.finished:
            self.notify("the run is still going: press a to abort it first")
            return
        self.app.pop_screen()

    def on_unmount(self) -> None:
        if not self.finished:
            self.session.observer.abort("the run screen was closed")
