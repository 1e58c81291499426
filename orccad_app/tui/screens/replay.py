"""A counterexample of the Check tab, replayed step by step — and run against the plant.

Each step is one instant of the counterexample on the composed automaton (what ``orccad check
--replay`` prints): its inputs and outputs, the statements the mission waits at afterwards
(highlighted in the source as on the run screen: reversed, the running ``run`` statements in
green) and the Robot-Tasks running; the instant where the property fails is marked ``✗`` (the
loop's first instant ``↻`` for a run that loops forever). ``r`` runs the counterexample's
inputs against the plant (the run screen, its report listing them)."""

from __future__ import annotations

from textual import on
from textual.app import ComposeResult
from textual.binding import Binding
from textual.containers import Horizontal, Vertical, VerticalScroll
from textual.screen import Screen
from textual.widgets import Footer, Header, OptionList, Static
from textual.widgets.option_list import Option

from orccad_app.reactive.status import Status
from orccad_app.tui.session import ScriptedInputs
from orccad_app.tui.status import elsewhere
from orccad_app.tui.widgets.source_view import SourceView
from orccad_app.tui.screens import orccad

__all__ = ["ReplayScreen"]


def _inputs(step) -> str:
    return ", ".join(name if value is None else f"{name}({value})"
                     for name, value in step.inputs) or "-"


class ReplayScreen(Screen):
    """Steps through ``replay`` (a :class:`~orccad_app.verify.replay.Replay`) of mission
    ``mission`` of ``path`` (whose text is ``text``); ``outcome`` is the failed property."""

    AUTO_FOCUS = "#replay-steps"

    BINDINGS = [
        Binding("right,n", "step(1)", "Next", tooltip="the next instant"),
        Binding("left,b", "step(-1)", "Back", tooltip="the previous instant"),
        Binding("home", "go('first')", "First", show=False, tooltip="the first instant"),
        Binding("f,end", "go('failing')", "Failing", tooltip="the instant where the "
                                                             "property fails"),
        Binding("r", "run", "Run on plant", tooltip="run the counterexample's inputs against "
                                                    "the plant (the run screen)"),
        Binding("escape", "app.pop_screen", "Back", tooltip="back to the Check tab"),
    ]

    def __init__(self, path: str, text: str, replay, outcome) -> None:
        super().__init__()
        self.path, self.text, self.replay, self.outcome = path, text, replay, outcome
        self.index = 0

    def compose(self) -> ComposeResult:
        yield Header()
        yield Static(id="replay-status")
        with Horizontal(id="replay-body"):
            yield OptionList(*self._options(), id="replay-steps")
            with Vertical(id="replay-main"):
                yield Static(id="replay-step")
                with VerticalScroll(id="replay-scroll"):
                    yield SourceView(id="replay-source")
        yield Footer(compact=True)

    def _options(self) -> list[Option]:
        options = []
        for index, step in enumerate(self.replay.steps):
            mark = self._symbol if step.mark else " "
            loop = "⟲ " if self.replay.loop_start is not None and \
                index >= self.replay.loop_start else ""
            when = "" if step.time_ns is None else f" @{step.time_ns / 1e9:g}"
            options.append(Option(f"{mark}{step.number:>3}{when} {loop}{_inputs(step)}"))
        return options

    @property
    def _symbol(self) -> str:
        return "✗" if self.replay.loop_start is None else "↻"

    def on_mount(self) -> None:
        self.title = f"ORCCAD — counterexample to {self.replay.name}"
        self.sub_title = self.path
        self.show(0)

    @property
    def step(self):
        return self.replay.steps[self.index]

    def show(self, index: int) -> None:
        """Show instant ``index`` (0-based): its text, the source where it waits."""
        if not self.replay.steps:
            self.query_one("#replay-status", Static).update(f"{self.replay.title}: no instant")
            return
        self.index = max(0, min(index, len(self.replay.steps) - 1))
        steps = self.query_one("#replay-steps", OptionList)
        if steps.highlighted != self.index:
            steps.highlighted = self.index
        step = self.step
        total = len(self.replay.steps)
        mark = f"   [b red]{self._symbol} {step.mark}[/]" if step.mark else ""
        replay = self.replay
        self.query_one("#replay-status", Static).update(
            f"{replay.kind} {replay.mission}.{replay.name}: {replay.message}\n"
            f"instant {step.number} of {total}{mark}")
        self.query_one("#replay-step", Static).update(self._step_text())
        waiting = step.lines_in(self.path)
        self.query_one("#replay-source", SourceView).show_run(
            self.path, self.text, waiting, step.run_lines_in(self.path),
            elsewhere(step.waiting, self.path))

    def _step_text(self) -> str:
        step = self.step
        when = "" if step.time_ns is None else f" at {step.time_ns / 1e9:g} s"
        lines = [f"[b]instant {step.number}{when}[/b]",
                 f"inputs:  {_inputs(step)}",
                 f"outputs: {', '.join(step.outputs) or '-'}"]
        if step.status != Status.RUNNING:
            lines.append(f"the mission has ended: {step.status}")
        for task in step.tasks:
            where = elsewhere([task.loc], self.path) or [f"line {task.loc.line}"]
            lines.append(f"running: {task.task} (run at {where[0]})")
        return "\n".join(lines)

    @on(OptionList.OptionHighlighted, "#replay-steps")
    def _highlighted(self, event: OptionList.OptionHighlighted) -> None:
        if event.option_index != self.index:
            self.show(event.option_index)

    def action_step(self, delta: int) -> None:
        self.show(self.index + delta)

    def action_go(self, where: str) -> None:
        self.show(0 if where == "first" else self.replay.failing)

    def action_run(self) -> None:
        """The counterexample's inputs against the plant: the run screen."""
        orccad(self).start_run(self.path, self.replay.mission, ScriptedInputs.of(self.outcome))
