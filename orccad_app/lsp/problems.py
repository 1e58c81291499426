"""The problems of an analysis as the protocol's diagnostics, per file.

A problem located in the document is shown there, its notes as related information. A
problem located in another file (an error inside an imported file) is shown twice: at the
``import`` in the document (the note the pipeline adds, "imported here"), pointing to the
real place, and in the imported file itself.
"""

from __future__ import annotations

from collections import defaultdict
from typing import Callable

from lsprotocol import types

from orccad_app.diagnostics import Diagnostic, SourceLocation
from orccad_app.lsp.analysis import Problem, Severity
from orccad_app.lsp.positions import TextLines, same_file, uri_of_path

__all__ = ["SOURCE", "to_range", "diagnostics_by_uri"]

#: The ``source`` of every diagnostic this server publishes.
SOURCE = "orccad"

_SEVERITIES = {
    Severity.ERROR: types.DiagnosticSeverity.Error,
    Severity.WARNING: types.DiagnosticSeverity.Warning,
    Severity.INFORMATION: types.DiagnosticSeverity.Information,
    Severity.HINT: types.DiagnosticSeverity.Hint,
}

TextOf = Callable[[str], "str | None"]


def to_range(location: SourceLocation, lines: TextLines | None) -> types.Range:
    """The protocol range of ``location`` (converted through ``lines``, the text of its
    file, when known; otherwise columns are taken as they are)."""
    if lines is None:
        lines = TextLines("")
    span = lines.span(location)
    return types.Range(types.Position(span.line, span.character),
                       types.Position(span.end_line, span.end_character))


def diagnostics_by_uri(path: str, text: str, problems: tuple[Problem, ...],
                       text_of: TextOf,
                       encoding: str = "utf-16") -> dict[str, list[types.Diagnostic]]:
    """The diagnostics of ``problems`` (found in the document ``path`` whose text is
    ``text``) for each file's URI; the document's URI is always a key. ``text_of(path)``
    gives another file's text (for its positions), or ``None``."""
    here = uri_of_path(path)
    lines = TextLines(text, encoding)
    cache: dict[str, TextLines | None] = {}

    def lines_of(file: str) -> TextLines | None:
        if same_file(file, path):
            return lines
        if file not in cache:
            other = text_of(file)
            cache[file] = None if other is None else TextLines(other, encoding)
        return cache[file]

    out: dict[str, list[types.Diagnostic]] = defaultdict(list)
    out[here] = []
    for problem in problems:
        related = [_related(note, lines_of) for note in problem.notes
                   if note.location is not None and note.location.line > 0]
        where = problem.location
        if where is None or where.line <= 0:
            where = SourceLocation(path, 1, 1)
        severity = _SEVERITIES[problem.severity]
        if same_file(where.file, path):
            out[here].append(types.Diagnostic(
                to_range(where, lines), problem.message, severity=severity, source=SOURCE,
                related_information=related or None))
            continue
        # in another file: at the import in this one, and in that file
        real = types.DiagnosticRelatedInformation(
            types.Location(uri_of_path(where.file), to_range(where, lines_of(where.file))),
            problem.message)
        anchor = next((n.location for n in reversed(problem.notes)
                       if n.location is not None and same_file(n.location.file, path)),
                      SourceLocation(path, 1, 1))
        out[here].append(types.Diagnostic(
            to_range(anchor, lines), f"in {where.file}: {problem.message}", severity=severity,
            source=SOURCE, related_information=[real, *related]))
        out[uri_of_path(where.file)].append(types.Diagnostic(
            to_range(where, lines_of(where.file)), problem.message, severity=severity,
            source=SOURCE, related_information=related or None))
    return dict(out)


def _related(note: Diagnostic, lines_of) -> types.DiagnosticRelatedInformation:
    assert note.location is not None
    return types.DiagnosticRelatedInformation(
        types.Location(uri_of_path(note.location.file),
                       to_range(note.location, lines_of(note.location.file))),
        note.message)
