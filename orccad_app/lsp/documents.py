"""The open documents as the server knows them: the editor's text (never the disk), the
latest analysis of each, and the reader that gives imports the unsaved buffers of other open
documents."""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from typing import Callable

from orccad_app.diagnostics import OrccadError
from orccad_app.lsp.analysis import Analysis, refusal
from orccad_app.lsp.index import Index
from orccad_app.lsp.tokens import Tok, tokens
from orccad_app.pipeline import read_source

__all__ = ["DocumentState", "buffer_reader", "depends_on", "text_of"]


@dataclass
class DocumentState:
    """What the server keeps of one open document between requests.

    :param uri: its URI; :param path: its file path.
    :param analysis: the latest analysis (of the version :attr:`analysed_version`).
    :param parsed: the latest analysis whose text parsed (kept while the text does not
        parse, for completion in scope).
    """

    uri: str
    path: str
    analysis: Analysis | None = None
    analysed_version: int | None = None
    parsed: Analysis | None = None
    _tokens: tuple[str, list[Tok]] | None = field(default=None, repr=False)
    _index: tuple[Analysis, Index] | None = field(default=None, repr=False)

    def index(self) -> Index | None:
        """The names of the latest parsed version (cached per analysis), or ``None``."""
        parsed = self.parsed
        if parsed is None or parsed.program is None:
            return None
        if self._index is None or self._index[0] is not parsed:
            self._index = (parsed, Index(parsed.program))
        return self._index[1]

    def tokens(self, text: str) -> list[Tok]:
        """The tokens of ``text`` (cached for the last text asked)."""
        if self._tokens is None or self._tokens[0] is not text:
            self._tokens = (text, tokens(text) if refusal(text) is None else [])
        return self._tokens[1]


def buffer_reader(buffers: dict[str, str]) -> Callable[[str], str]:
    """A reader for imported files: the unsaved text of an open document (``buffers`` maps
    real paths to texts), else the file on disk (:func:`~orccad_app.pipeline.read_source`,
    with its budget and errors)."""

    def read(path: str) -> str:
        text = buffers.get(os.path.realpath(path))
        if text is None:
            return read_source(path)
        why = refusal(text)
        if why is not None:
            raise OrccadError(f"{path}: {why}")
        return text

    return read


def text_of(buffers: dict[str, str]) -> Callable[[str], str | None]:
    """The text of a file for its positions: its open buffer, else the disk, else ``None``."""

    def read(path: str) -> str | None:
        try:
            return buffer_reader(buffers)(path)
        except OrccadError:
            return None

    return read


def depends_on(analysis: Analysis, path: str) -> bool:
    """Whether ``analysis`` read ``path`` (an import) or reports a problem located in it."""
    real = os.path.realpath(path)
    if any(os.path.realpath(p) == real for p in analysis.imported):
        return True
    for problem in analysis.problems:
        for where in (problem.location, *(n.location for n in problem.notes)):
            if where is not None and where.line > 0 and os.path.realpath(where.file) == real:
                return True
    return False
