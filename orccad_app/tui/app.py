"""``orccad tui``: the mission runner (see ``docs/tui.md``).

The app only routes between screens; what the screens show comes from the same functions as
the CLI (:mod:`orccad_app.tui.session`) and from an executive observer
(:mod:`orccad_app.tui.live`).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

from textual.app import App
from textual.binding import Binding

from orccad_app.diagnostics import OrccadError
from orccad_app.tui.commands import OrccadCommands
from orccad_app.tui.messages import RunUpdated
from orccad_app.tui.screens.help import HelpScreen
from orccad_app.tui.screens.browser import BrowserScreen
from orccad_app.tui.screens.campaign import CampaignScreen
from orccad_app.tui.screens.report import ReportScreen
from orccad_app.tui.screens.run import RunScreen
from orccad_app.tui.session import LiveSession, ScriptedInputs, mission_files

if TYPE_CHECKING:
    from orccad_app.campaign.setting import RunSetting
    from orccad_app.tui.screens import ScreenHost

__all__ = ["OrccadApp"]


class OrccadApp(App):
    """The terminal UI.

    :param paths: files and folders to browse (``missions/`` is always added when it exists).
    :param selected: the file shown first (default: the first one).
    :param speed: initial speed of runs (sim s per wall s; ``None`` as fast as possible).
    :param seed: the runs' seed.
    :param run_now: start running ``selected`` at once.
    """

    CSS_PATH = "orccad.tcss"
    TITLE = "ORCCAD"
    HORIZONTAL_BREAKPOINTS = [(0, "-narrow"), (120, "-wide")]
    BINDINGS = [Binding("question_mark,f1", "help", "Help", tooltip="the keys of this screen"),
                Binding("f12", "screenshot_svg", "Screenshot", show=False,
                        tooltip="save an SVG screenshot")]
    COMMANDS = App.COMMANDS | {OrccadCommands}

    def __init__(self, paths: Sequence[str] = (), *, selected: str | None = None,
                 mission: str | None = None, speed: float | None = 1.0, seed: int = 0,
                 run_now: bool = False, campaign: dict[str, Any] | None = None) -> None:
        super().__init__()
        self.files = mission_files([*paths, "missions"])
        self.given = selected
        """The file named on the command line (``None``: the browser's first is shown)."""
        self.selected = selected or (self.files[0] if self.files else None)
        self.mission = mission
        self.speed = speed
        self.seed = seed
        self.run_now = run_now
        self.campaign = campaign
        self.session: LiveSession | None = None

    def on_mount(self) -> None:
        self.push_screen(BrowserScreen(self.files, self.selected))
        if self.run_now and self.selected:
            self.start_run(self.selected, self.mission)
        elif self.campaign is not None:  # a database alone names its own mission file
            self.open_campaign(self.given, **self.campaign)

    def open_campaign(self, path: str | None, spec: str | None = None,
                      db: str | None = None, **options: Any) -> None:
        """The campaign screen for mission file ``path`` with campaign spec ``spec`` (default:
        the ``.campaign.toml`` beside it), or for the existing database ``db``."""
        from orccad_app.tui.campaigns import default_spec

        spec = spec or (default_spec(path) if path else None)
        self.push_screen(CampaignScreen(path, spec, db, **options))

    def start_run(self, path: str, mission: str | None, script: ScriptedInputs | None = None,
                  *, setting: RunSetting | None = None, by: str = "") -> None:
        """Plan ``mission`` of ``path`` (as ``orccad run`` does) and show its live run
        (``script``: a counterexample's inputs injected at its instants' times; ``setting``:
        a campaign run's :class:`~orccad_app.campaign.setting.RunSetting`, raised ``by``)."""
        screen: RunScreen | None = None

        def post(update) -> None:
            if screen is not None:
                screen.post_message(RunUpdated(update))

        try:
            self.session = LiveSession(path, mission, post, speed=self.speed, seed=self.seed,
                                       script=script, setting=setting, by=by,
                                       wait_for_screen=True, own_process=True)
        except OrccadError as error:
            self.notify(error.format(), severity="error", timeout=10)
            return
        screen = RunScreen(self.session)
        self.push_screen(screen)

    def show_report(self, session: LiveSession, report: str) -> None:
        """Show the final report of a finished run."""
        self.push_screen(ReportScreen(session, report))

    def action_help(self) -> None:
        """The keys of the current screen."""
        if not isinstance(self.screen, HelpScreen):
            self.push_screen(HelpScreen(self.screen))

    def open_file(self, path: str) -> None:
        """Back to the mission browser, showing ``path``."""
        while len(self.screen_stack) > 2 and not isinstance(self.screen, BrowserScreen):
            if isinstance(self.screen, RunScreen) and not self.screen.finished:
                self.notify("a run is going: abort it (a) before opening another file",
                            severity="warning")
                return
            self.pop_screen()
        if isinstance(self.screen, BrowserScreen):
            self.screen.select(path)

    def action_screenshot_svg(self) -> None:
        self.notify(f"saved {self.save_screenshot()}")


if TYPE_CHECKING:
    def _hosts_the_screens(app: OrccadApp) -> ScreenHost:
        return app  # mypy checks that the application is what the screens ask for
