"""Edit a mission in place: the ``orc`` highlighting, live diagnostics as you type (compiled
in a worker, the error lines marked), a diagnostics list that jumps to the line, save
(atomic), and reload when the file changes on disk."""

from __future__ import annotations

from pathlib import Path

from rich.style import Style
from textual import on, work
from textual.app import ComposeResult
from textual.binding import Binding
from textual.containers import Vertical
from textual.message import Message
from textual.screen import Screen
from textual.widgets import Footer, Header, OptionList, TextArea
from textual.widgets._text_area import TextAreaTheme
from textual.widgets.option_list import Option

from orccad_app.diagnostics import OrccadError
from orccad_app.tui.session import (FileView, inspect_text, one_line, source_text,
                                    write_atomically)
from orccad_app.tui.widgets.orc_lexer import OrcLexer

__all__ = ["EditorScreen", "OrcTextArea"]

_TOKEN_NAMES = (("Comment", "comment"), ("String", "string"), ("Number", "number"),
                ("Keyword.Declaration", "keyword"), ("Keyword.Constant", "boolean"),
                ("Keyword", "keyword"), ("Name.Class", "type"), ("Operator", "operator"))


def _highlight_name(token) -> str | None:
    text = str(token).removeprefix("Token.")
    for prefix, name in _TOKEN_NAMES:
        if text == prefix or text.startswith(prefix + "."):
            return name
    return None


class OrcTextArea(TextArea):
    """A TextArea highlighting the plan language with the source view's lexer (Textual's
    own highlighting needs a tree-sitter grammar, which ``orc`` has not), and marking the
    lines of :attr:`error_lines`."""

    _lexer = OrcLexer()
    error_lines: frozenset[int] = frozenset()  # 1-based

    def _build_highlight_map(self) -> None:
        self._line_cache.clear()
        highlights = self._highlights
        highlights.clear()
        row, col = 0, 0
        for _, token, value in self._lexer.get_tokens_unprocessed(self.text):
            name = _highlight_name(token)
            for index, part in enumerate(value.split("\n")):
                if index:
                    row, col = row + 1, 0
                if name and part:
                    highlights[row].append((col, col + len(part), name))
                col += len(part)
        for line in self.error_lines:
            highlights[line - 1].insert(0, (0, None, "orc.error"))

    def mark_errors(self, lines: set[int]) -> None:
        self.error_lines = frozenset(lines)
        self._build_highlight_map()
        self.refresh()


class _Checked(Message):
    def __init__(self, view: FileView, text: str) -> None:
        super().__init__()
        self.view = view
        self.text = text


class EditorScreen(Screen[bool]):
    """Edits ``path``; dismisses with ``True`` when something was saved."""

    AUTO_FOCUS = "#editor"

    BINDINGS = [
        Binding("ctrl+s", "save", "Save", tooltip="save the file (atomically)"),
        Binding("ctrl+r", "reload", "Reload", tooltip="reload the file from the disk"),
        Binding("f8", "next_diagnostic", "Next diagnostic",
                tooltip="jump to the next diagnostic's line"),
        Binding("escape", "close", "Close", tooltip="back to the browser (twice if unsaved)"),
    ]

    DEFAULT_CSS = """
    EditorScreen #editor { height: 1fr; }
    EditorScreen #diagnostics { height: 7; border-top: solid $primary; }
    """

    def __init__(self, path: str, text: str) -> None:
        """Edit ``path``, whose text ``text`` was read by
        :func:`~orccad_app.tui.session.source_text` (never a binary file or a FIFO)."""
        super().__init__()
        self.path = path
        self.saved_text = text
        self.diagnostics: list = []
        self.saved = False
        self._mtime = Path(path).stat().st_mtime_ns
        self._close_armed = False

    def compose(self) -> ComposeResult:
        yield Header()
        with Vertical():
            editor = OrcTextArea(self.saved_text, id="editor", show_line_numbers=True,
                                 tab_behavior="indent")
            yield editor
            yield OptionList(id="diagnostics")
        yield Footer(compact=True)

    def on_mount(self) -> None:
        theme = TextAreaTheme.get_builtin_theme("monokai")
        if theme is None:  # Textual ships it; without it the editor keeps its default theme
            return
        styles = dict(theme.syntax_styles)
        styles["orc.error"] = Style(bgcolor="#5f0000")
        editor = self.query_one(OrcTextArea)
        editor.register_theme(TextAreaTheme("orc", base_style=theme.base_style,
                                            gutter_style=theme.gutter_style,
                                            cursor_style=theme.cursor_style,
                                            cursor_line_style=theme.cursor_line_style,
                                            selection_style=theme.selection_style,
                                            syntax_styles=styles))
        editor.theme = "orc"
        self.title = "ORCCAD — edit"
        self._sub_title()
        self.set_interval(1.0, self._watch_disk)
        self._check(self.saved_text)

    @property
    def modified(self) -> bool:
        return self.query_one(OrcTextArea).text != self.saved_text

    def _sub_title(self) -> None:
        self.sub_title = f"{self.path}{' (modified)' if self.modified else ''}"

    @on(TextArea.Changed, "#editor")
    def _changed(self) -> None:
        self._close_armed = False
        self._sub_title()
        self._check(self.query_one(OrcTextArea).text)

    @work(thread=True, exclusive=True, group="diagnostics")
    def _check(self, text: str) -> None:
        """Compile the text as ``orccad compile`` would (the latest edit wins)."""
        import time

        time.sleep(0.3)  # typing: wait for a pause (an exclusive worker cancels older ones)
        from textual.worker import get_current_worker

        if get_current_worker().is_cancelled:
            return
        self.post_message(_Checked(inspect_text(self.path, text), text))

    @on(_Checked)
    def _checked(self, message: _Checked) -> None:
        editor = self.query_one(OrcTextArea)
        if message.text != editor.text:
            return  # an older text
        self.diagnostics = message.view.diagnostics
        options = self.query_one("#diagnostics", OptionList)
        options.clear_options()
        if not self.diagnostics:
            options.add_option(Option("no diagnostics: the file compiles", disabled=True))
        for diagnostic in self.diagnostics:
            options.add_option(Option(diagnostic.format()))
        editor.mark_errors({d.line for d in self.diagnostics
                            if d.severity == "error" and d.line})

    @on(OptionList.OptionSelected, "#diagnostics")
    def _jump(self, event: OptionList.OptionSelected) -> None:
        self.jump_to(event.option_index)

    def jump_to(self, index: int) -> None:
        """Move the cursor to diagnostic ``index``'s line and column."""
        if not 0 <= index < len(self.diagnostics):
            return
        diagnostic = self.diagnostics[index]
        editor = self.query_one(OrcTextArea)
        editor.move_cursor((max(0, diagnostic.line - 1), max(0, diagnostic.col - 1)),
                           center=True)
        editor.focus()

    def action_next_diagnostic(self) -> None:
        if not self.diagnostics:
            self.notify("no diagnostics")
            return
        row = self.query_one(OrcTextArea).cursor_location[0] + 1
        later = [i for i, d in enumerate(self.diagnostics) if d.line > row]
        self.jump_to(later[0] if later else 0)

    def action_save(self) -> None:
        text = self.query_one(OrcTextArea).text
        try:
            def write(tmp: Path) -> None:
                tmp.write_text(text, encoding="utf-8")

            write_atomically(self.path, write)
        except OSError as error:
            self.notify(f"cannot save {self.path}: {error.strerror}", severity="error")
            return
        self.saved_text, self.saved = text, True
        self._mtime = Path(self.path).stat().st_mtime_ns
        self._sub_title()
        errors = sum(1 for d in self.diagnostics if d.severity == "error")
        self.notify(f"saved {self.path}" + (f" ({errors} error{'s' * (errors > 1)})"
                                             if errors else ""))

    def _watch_disk(self) -> None:
        try:
            mtime = Path(self.path).stat().st_mtime_ns
        except OSError:
            return
        if mtime == self._mtime:
            return
        self._mtime = mtime
        if self.modified:
            self.notify(f"{self.path} changed on disk: ctrl+r reloads it (your edits are lost)",
                        severity="warning", timeout=8)
        else:
            self.action_reload()

    def action_reload(self) -> None:
        try:
            text = source_text(self.path)  # replaced on disk by a binary file: said, kept
        except OrccadError as error:
            self.notify(f"cannot reload {one_line(error)}", severity="error", timeout=10)
            return
        self.saved_text = text
        self.query_one(OrcTextArea).load_text(text)
        self._sub_title()
        self.notify(f"reloaded {self.path}")

    def action_close(self) -> None:
        if self.modified and not self._close_armed:
            self._close_armed = True
            self.notify("unsaved changes: ctrl+s saves, esc again discards them",
                        severity="warning")
            return
        self.dismiss(self.saved)
