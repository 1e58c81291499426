"""Screens of the terminal UI: the mission browser, the run, the report."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, Protocol, cast

if TYPE_CHECKING:
    from textual.screen import Screen

    from orccad_app.campaign.setting import RunSetting
    from orccad_app.tui.session import LiveSession, ScriptedInputs

__all__ = ["ScreenHost", "orccad"]


class ScreenHost(Protocol):
    """What the screens ask of their application (:class:`~orccad_app.tui.app.OrccadApp`)."""

    def open_campaign(self, path: str | None, spec: str | None = None,
                      db: str | None = None, **options: Any) -> None: ...

    def start_run(self, path: str, mission: str | None, script: ScriptedInputs | None = None,
                  *, setting: RunSetting | None = None, by: str = "") -> None: ...

    def show_report(self, session: LiveSession, report: str) -> None: ...


def orccad(screen: Screen) -> ScreenHost:
    """The screen's application as :class:`ScreenHost` (Textual's ``Screen.app`` is an
    ``App[Any]``); every screen of this package runs in ``OrccadApp``."""
    return cast("ScreenHost", screen.app)
