"""The source of a ``.orc`` file, highlighted, with its diagnostics at their lines."""

from __future__ import annotations

from collections.abc import Sequence

from rich.console import Group, RenderableType
from rich.syntax import Syntax
from rich.text import Text
from textual.widget import Widget
from textual.widgets import Static

from orccad_app.tui.widgets.orc_lexer import OrcLexer

__all__ = ["SourceView"]

_STYLE = {"error": "bold red", "warning": "bold yellow"}


class SourceView(Static):
    """Shows a :class:`~orccad_app.tui.session.FileView`: the diagnostics, then the source
    with their lines highlighted and a marker under each."""

    DEFAULT_CSS = """
    SourceView { height: auto; padding: 0 1; }
    """

    def show(self, view) -> None:
        """Render ``view`` (a ``FileView``)."""
        parts: list[RenderableType] = []
        for diagnostic in view.diagnostics:
            parts.append(Text(f"{view.path}:{diagnostic.format()}",
                              style=_STYLE.get(diagnostic.severity, "")))
        if not view.diagnostics:
            parts.append(Text(f"{view.path}: no diagnostics", style="green"))
        lines = {d.line for d in view.diagnostics if d.line}
        syntax = Syntax(view.text, OrcLexer(), line_numbers=True, highlight_lines=lines,
                        theme="monokai", word_wrap=False)
        for diagnostic in view.diagnostics:
            if diagnostic.line:
                syntax.stylize_range(_STYLE.get(diagnostic.severity, "") + " underline",
                                     (diagnostic.line, 0), (diagnostic.line + 1, 0))
        parts.append(Text(""))
        parts.append(syntax)
        self.update(Group(*parts))

    def show_run(self, path: str, text: str, lines: list[int],
                 sites: Sequence[int] = (), elsewhere: Sequence[str] = ()) -> None:
        """The mission's source with the lines it waits at highlighted (reversed) and the
        ``run`` statements of the running Robot-Tasks (green), scrolled into view;
        ``elsewhere`` (``homing.orc:26``) says where it waits in other files."""
        caption = (Text(f"{path}: waiting at line{'s' if len(lines) > 1 else ''} "
                        f"{', '.join(map(str, lines))}", style="bold yellow") if lines else
                   Text(f"{path}: not waiting at a statement", style="dim"))
        if elsewhere:
            caption.append(f"   in {', '.join(elsewhere)}", style="bold yellow")
        if sites:
            caption.append(f"   running: line{'s' if len(sites) > 1 else ''} "
                           f"{', '.join(map(str, sites))}", style="bold green")
        syntax = Syntax(text, OrcLexer(), line_numbers=True, highlight_lines=set(lines),
                        theme="monokai", word_wrap=False)
        for line in sites:
            syntax.stylize_range("bold black on green", (line, 0), (line + 1, 0))
        for line in lines:
            syntax.stylize_range("bold reverse", (line, 0), (line + 1, 0))
        self.update(Group(caption, Text(""), syntax))
        self.sites = list(sites)
        self.waiting = lines
        parent = self.parent
        if lines and isinstance(parent, Widget):
            parent.scroll_to(y=max(0, lines[0] - 4), animate=False)
