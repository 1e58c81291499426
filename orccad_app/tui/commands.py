"""The command palette's own commands (``ctrl+p``): open a mission, run, check, inject a given
fault or event, raise an input, export the trace, set the speed, show the keys."""

from __future__ import annotations

from collections.abc import Callable
from functools import partial

from textual.command import DiscoveryHit, Hit, Hits, Provider

__all__ = ["OrccadCommands", "commands_for"]


def commands_for(app, screen) -> list[tuple[str, Callable[[], None], str]]:
    """``(title, callback, help)`` of what can be done on ``screen`` now."""
    from orccad_app.tui.screens.browser import BrowserScreen
    from orccad_app.tui.screens.report import ReportScreen
    from orccad_app.tui.screens.replay import ReplayScreen
    from orccad_app.tui.screens.run import RunScreen
    from orccad_app.tui.session import failed_outcomes

    found = [("Help: the keys of this screen", app.action_help, "? or F1")]
    if isinstance(screen, BrowserScreen):
        found += [("Run the mission", screen.action_run, "r: run it live"),
                  ("Check the mission's properties", screen.action_check, "c: orccad check"),
                  ("Edit the mission", screen.action_edit, "with live diagnostics")]
        outcomes = failed_outcomes(screen.report) if screen.report is not None else []
        for outcome in outcomes:
            found += [(f"Replay the counterexample to {outcome.name}",
                       partial(screen.action_replay, outcome), "step by step, where it waits"),
                      (f"Run the counterexample to {outcome.name} against the plant",
                       partial(screen.run_counterexample, outcome),
                       "its inputs injected at their instants")]
    if isinstance(screen, ReplayScreen):
        found += [("Run this counterexample against the plant", screen.action_run,
                   "r: its inputs injected at their instants"),
                  ("Go to the instant where the property fails",
                   partial(screen.action_go, "failing"), "f")]
    if isinstance(screen, RunScreen) and not screen.finished:
        bar = screen.session
        for signal in bar.inputs:
            found.append((f"Raise input {signal.name}",
                          partial(screen.raise_named, signal.name), "as its key does"))
        for name in bar.events:
            found.append((f"Raise event {name}", partial(screen.raise_named, name),
                          "what the observer would raise"))
        for name, text in bar.faults.items():
            found.append((f"Inject fault {name}", partial(screen.raise_named, name),
                          f"{text} (value from the value field)"))
        for label, speed in (("Speed: real time (1×)", "realtime"), ("Speed: 10×", "fast"),
                             ("Speed: as fast as possible", "max"), ("Pause", "pause")):
            found.append((label, partial(screen.action_speed, speed), "pacing"))
        found.append(("Abort the run", screen.action_abort, "status aborted"))
    if isinstance(screen, ReportScreen):
        found.append(("Export the trace", screen.action_export, "to the path in the field"))
    for path in app.files:  # after what this screen does
        found.append((f"Open mission {path}", partial(app.open_file, path),
                      "show it in the mission browser"))
    return found


class OrccadCommands(Provider):
    """The app's commands, fuzzy-matched."""

    async def discover(self) -> Hits:
        for title, callback, help_text in commands_for(self.app, self.screen):
            yield DiscoveryHit(title, callback, help=help_text)

    async def search(self, query: str) -> Hits:
        matcher = self.matcher(query)
        for title, callback, help_text in commands_for(self.app, self.screen):
            score = matcher.match(title)
            if score > 0:
                yield Hit(score, matcher.highlight(title), callback, help=help_text)
