"""The mission browser: files, source with diagnostics, compile summary, ``orccad check``."""

from __future__ import annotations

from typing import TYPE_CHECKING

from textual import on, work
from textual.app import ComposeResult
from textual.binding import Binding
from textual.containers import Horizontal, VerticalScroll
from textual.screen import Screen
from textual.containers import Vertical
from textual.widgets import (Button, Footer, Header, Input, Label, ListItem, ListView,
                             OptionList, Select, Static, TabbedContent, TabPane, TextArea)
from textual.widgets.option_list import Option

from orccad_app.diagnostics import OrccadError
from orccad_app.tui.messages import CheckDone
from orccad_app.tui.session import (FileView, ScriptedInputs, check_file, check_text,
                                    failed_outcomes, inspect_file, one_line,
                                    source_text)
from orccad_app.tui.widgets.source_view import SourceView
from orccad_app.tui.screens import orccad

if TYPE_CHECKING:
    from orccad_app.verify.checker import MissionReport

__all__ = ["BrowserScreen"]


class BrowserScreen(Screen):
    """Lists ``files``; shows the selected one's source, summary and check results."""

    AUTO_FOCUS = "#files"

    BINDINGS = [
        Binding("r", "run", "Run", tooltip="run the selected mission live"),
        Binding("c", "check", "Check", tooltip="prove its properties (orccad check)"),
        Binding("s", "show_tab('source')", "Source", tooltip="show the source"),
        Binding("m", "show_tab('summary')", "Summary", tooltip="show the compile summary"),
        Binding("p", "replay", "Replay", show=False, tooltip="replay the counterexample chosen in the Check "
                                                 "tab step by step (r there runs it on the "
                                                 "plant)"),
        Binding("ctrl+e", "edit", "Edit", tooltip="edit it with live diagnostics"),
        Binding("k", "campaign", "Campaign", show=False, tooltip="campaigns and falsification of it "
                                                     "(its .campaign.toml spec)"),
        Binding("slash", "search", "Search", tooltip="type to filter the mission list"),
        Binding("q", "app.quit", "Quit"),
    ]

    EMPTY = ("No mission here. Start `orccad tui FILE.orc` or `orccad tui FOLDER` from where your "
             "missions are (missions/ is listed when it exists), or write one: see "
             "docs/language.md. Then select it on the left: up/down preview, enter opens.")

    def __init__(self, files: list[str], selected: str | None = None) -> None:
        super().__init__()
        self.files = files
        self.selected = selected or (files[0] if files else None)
        self.view: FileView | None = None
        self.report: MissionReport | None = None
        """The last ``orccad check`` report (its counterexamples are replayed)."""

    def compose(self) -> ComposeResult:
        yield Header()
        with Horizontal():
            with Vertical(id="files-column"):
                yield Input(placeholder="/ search missions", id="files-search", compact=True)
                yield ListView(*self._items(self.files), id="files")
            with TabbedContent(id="tabs"):
                with TabPane("Source", id="source"):
                    with VerticalScroll():
                        yield SourceView(id="source-view")
                with TabPane("Summary", id="summary"):
                    yield Select([], id="mission", prompt="mission", allow_blank=True)
                    yield TextArea(id="summary-text", read_only=True, soft_wrap=False)
                with TabPane("Check", id="check"):
                    with Horizontal(id="check-bar"):
                        yield Button("Check properties (orccad check)", id="check-button")
                        yield Button("Run", id="run-button", variant="primary")
                    yield OptionList(id="counterexamples")
                    with VerticalScroll():
                        yield Static("press c to prove the mission's properties",
                                     id="check-text")
        yield Footer(compact=True)

    @staticmethod
    def _items(paths: list[str]) -> list[ListItem]:
        """One item per file, named by its path; shown without the ``missions/`` folder (so
        that a narrow list still tells ``arm_pid.orc`` from ``arm_retune.orc``)."""
        return [ListItem(Label(path.removeprefix("missions/")), name=path) for path in paths]

    def on_mount(self) -> None:
        self.title = "ORCCAD — missions"
        if not self.files:
            self.query_one("#source-view", SourceView).update(self.EMPTY)
            self.query_one("#check-text", Static).update(self.EMPTY)
        if self.selected is not None:
            files = self.query_one("#files", ListView)
            if self.selected in self.files:
                files.index = self.files.index(self.selected)
            self.open(self.selected)

    @property
    def mission(self) -> str | None:
        value = self.query_one("#mission", Select).value
        if isinstance(value, str):
            return value
        return self.view.missions[0] if self.view and self.view.missions else None

    def open(self, path: str) -> None:
        """Show ``path``: source, diagnostics, compile summary of each mission."""
        self.selected = path
        self.view = view = inspect_file(path)
        self.sub_title = path
        self.query_one(SourceView).show(view)
        select = self.query_one("#mission", Select)
        select.set_options([(name, name) for name in view.missions])
        if view.missions:
            select.value = view.missions[0]
        self._show_summary()
        self._show_counterexamples(None)
        self.query_one("#check-text", Static).update(
            "press c to prove the mission's properties (orccad check)")

    def _show_summary(self) -> None:
        view, text = self.view, "no mission in this file"
        if view is not None and not view.ok:
            text = "\n".join(d.format() for d in view.diagnostics if d.severity == "error")
        elif view is not None and self.mission in view.summaries:
            inputs = ", ".join(view.inputs[self.mission]) or "none"
            text = f"{view.summaries[self.mission]}\n\ndeclared inputs: {inputs}"
        self.query_one("#summary-text", TextArea).load_text(text)

    @on(ListView.Selected, "#files")
    @on(ListView.Highlighted, "#files")
    def _file_selected(self, event) -> None:
        """Enter opens, and so do the arrow keys (a preview of the highlighted file)."""
        if event.item is not None and event.item.name and event.item.name != self.selected:
            self.open(event.item.name)

    def select(self, path: str) -> None:
        """Show ``path`` and highlight it in the list (the command palette's "open")."""
        files = self.query_one("#files", ListView)
        names = [item.name for item in files.query(ListItem)]
        if path in names:
            files.index = names.index(path)
        self.open(path)

    def action_search(self) -> None:
        self.query_one("#files-search", Input).focus()

    @on(Input.Changed, "#files-search")
    def _search(self, event: Input.Changed) -> None:
        """Keep the files whose path contains the text typed (case-insensitive)."""
        text = event.value.strip().lower()
        shown = [path for path in self.files if text in path.lower()]
        files = self.query_one("#files", ListView)
        files.clear()
        files.extend(self._items(shown))
        if not shown:
            files.append(ListItem(Label(f"no file matches {event.value!r}")))

    @on(Input.Submitted, "#files-search")
    def _search_done(self) -> None:
        files = self.query_one("#files", ListView)
        files.focus()
        if files.children:
            files.index = 0
            name = getattr(files.children[0], "name", None)
            if name:
                self.open(name)

    def action_edit(self) -> None:
        if self.selected is None:
            self.notify("no file to edit", severity="warning")
            return
        from orccad_app.tui.screens.editor import EditorScreen

        try:
            text = source_text(self.selected)  # a binary file or a FIFO is never opened
        except OrccadError as error:
            self.notify(f"cannot edit {one_line(error)}", severity="error", timeout=10)
            return

        def edited(saved: bool | None) -> None:
            if saved and self.selected is not None:
                self.open(self.selected)

        self.app.push_screen(EditorScreen(self.selected, text), edited)

    @on(Select.Changed, "#mission")
    def _mission_changed(self) -> None:
        self._show_summary()

    def action_show_tab(self, tab: str) -> None:
        self.query_one("#tabs", TabbedContent).active = tab

    @on(Button.Pressed, "#check-button")
    def action_check(self) -> None:
        if self.view is None or not self.view.ok or self.mission is None:
            self.notify("nothing to check: the file has errors or no mission", severity="error")
            return
        self.action_show_tab("check")
        self.query_one("#check-text", Static).update(f"checking {self.mission}…")
        self._check(self.view, self.mission)

    @work(thread=True, exclusive=True, group="check")
    def _check(self, view: FileView, mission: str) -> None:
        try:
            report = check_file(view, mission)
        except ImportError as error:  # the verifier is an optional part of the core
            self.post_message(CheckDone(mission, f"orccad check unavailable: {error}", False))
            return
        except Exception as error:  # a diagnostic for the user, not a crash of the UI
            self.post_message(CheckDone(mission, f"check failed: {error}", False))
            return
        self.post_message(CheckDone(mission, check_text(report), report.holds, report))

    @on(CheckDone)
    def _check_done(self, message: CheckDone) -> None:
        self.query_one("#check-text", Static).update(message.text)
        self._show_counterexamples(message.report)
        self.notify(f"{message.mission}: " + ("all properties hold" if message.holds
                                              else "a property fails"),
                    severity="information" if message.holds else "warning")

    def _show_counterexamples(self, report) -> None:
        """List the failed properties of ``report`` above the check's text."""
        self.report = report
        failed = [] if report is None else failed_outcomes(report)
        options = self.query_one("#counterexamples", OptionList)
        options.clear_options()
        options.add_options([Option(f"✗ {o.name}: {o.message}") for o in failed])
        options.border_title = "counterexamples: enter replays one step by step"
        options.display = bool(failed)
        if failed:
            options.highlighted = 0
            options.focus()

    @property
    def outcome(self):
        """The failed property chosen in the Check tab (``None`` without one)."""
        failed = failed_outcomes(self.report) if self.report is not None else []
        index = self.query_one("#counterexamples", OptionList).highlighted
        return failed[index] if failed and index is not None and index < len(failed) else None

    @on(OptionList.OptionSelected, "#counterexamples")
    def _counterexample_chosen(self) -> None:
        self.action_replay()

    def action_replay(self, outcome=None) -> None:
        """Replay ``outcome`` (default: the counterexample chosen in the Check tab) step by
        step: the replay screen."""
        from orccad_app.tui.screens.replay import ReplayScreen
        from orccad_app.verify.replay import replay

        outcome = outcome or self.outcome
        if outcome is None or self.view is None or self.report is None:
            self.notify("no counterexample: press c to check the mission, then choose a "
                        "failed property in the Check tab", severity="warning")
            return
        composition = self.report.composition
        self.app.push_screen(ReplayScreen(self.view.path, self.view.text,
                                          replay(composition, outcome), outcome))

    def run_counterexample(self, outcome) -> None:
        """Run ``outcome``'s counterexample against the plant (the command palette)."""
        if self.view is None or self.report is None:
            return
        orccad(self).start_run(self.view.path, self.report.composition.name,
                           ScriptedInputs.of(outcome))

    @on(Button.Pressed, "#run-button")
    def action_run(self) -> None:
        if self.view is None or not self.view.ok or self.mission is None:
            self.notify("cannot run: the file has errors or no mission", severity="error")
            return
        orccad(self).start_run(self.view.path, self.mission)

    def action_campaign(self) -> None:
        if self.selected is None:
            self.notify("choose a mission file first", severity="warning")
            return
        orccad(self).open_campaign(self.selected)
