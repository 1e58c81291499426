"""One document analysed by the compiler pipeline: its AST (when it parses), its checked
:class:`~orccad_app.pipeline.Source` (when it passes), and every problem found, located.

The pipeline is the command line's (:func:`~orccad_app.pipeline.check_source`), with two
differences: the text is the editor's buffer, and imported files are read through
``read`` (which prefers the buffers of other open documents to the disk).
"""

from __future__ import annotations

import enum
from dataclasses import dataclass, field
from typing import Callable

from orccad_app.diagnostics import Diagnostic, OrccadError, SourceLocation
from orccad_app.lang import ast
from orccad_app.lang.parser import parse
from orccad_app.pipeline import MAX_SOURCE_BYTES, Source, check_source

__all__ = ["Severity", "Problem", "Analysis", "analyze", "refusal", "problems_of"]


class Severity(str, enum.Enum):
    """How bad a problem is (the protocol's diagnostic severities)."""

    ERROR = "error"
    WARNING = "warning"
    INFORMATION = "information"
    HINT = "hint"


@dataclass(frozen=True)
class Problem:
    """One located message, with the notes that explain it (each located too)."""

    severity: Severity
    message: str
    location: SourceLocation | None
    notes: tuple[Diagnostic, ...] = ()


@dataclass(frozen=True)
class Analysis:
    """What the pipeline made of one version of a document.

    :param path: the document's file path (imports are resolved from its folder).
    :param text: the text analysed.
    :param program: its AST, ``None`` when it does not parse (or was refused).
    :param source: the checked file, ``None`` when the checks failed.
    :param problems: every error and warning, in the pipeline's order.
    :param imported: the paths of the files its imports loaded (when it passed).
    """

    path: str
    text: str
    program: ast.Program | None = None
    source: Source | None = None
    problems: tuple[Problem, ...] = ()
    imported: tuple[str, ...] = field(default_factory=tuple)

    @property
    def checked(self) -> bool:
        """The document passed every check."""
        return self.source is not None


def refusal(text: str) -> str | None:
    """Why ``text`` is not analysed at all (checked before any work), or ``None``: a buffer
    over the source budget, or one holding NUL characters (a binary file)."""
    size = len(text.encode("utf-8", "surrogatepass"))
    if size > MAX_SOURCE_BYTES:
        return (f"not analysed: {size} bytes, larger than the {MAX_SOURCE_BYTES} bytes a "
                "source file may have (see docs/limits.md)")
    if "\0" in text:
        return "not analysed: a binary file (it holds NUL characters), not plan-language text"
    return None


def problems_of(error: OrccadError) -> list[Problem]:
    """The problems of one raised error: the checker raises the first of several errors
    with the others as ``error`` notes; each becomes its own problem, with its own notes."""
    found = [Problem(Severity.ERROR, error.message, error.location)]
    notes: list[Diagnostic] = []
    for note in error.notes:
        if note.severity == "error":
            found[-1] = _with_notes(found[-1], notes)
            found.append(Problem(Severity.ERROR, note.message, note.location))
            notes = []
        else:
            notes.append(note)
    found[-1] = _with_notes(found[-1], notes)
    return found


def _with_notes(problem: Problem, notes: list[Diagnostic]) -> Problem:
    return Problem(problem.severity, problem.message, problem.location, tuple(notes))


def _warning(diagnostic: Diagnostic) -> Problem:
    severity = Severity.WARNING if diagnostic.severity == "warning" else Severity.INFORMATION
    return Problem(severity, diagnostic.message, diagnostic.location)


def analyze(path: str, text: str, read: Callable[[str], str], host=None) -> Analysis:
    """Parse and check ``text`` (the document at ``path``); never raises on bad input.

    ``read(path)`` gives an imported file's text; ``host`` is the plugin host the
    Robot-Tasks are checked against."""
    why = refusal(text)
    if why is not None:
        return Analysis(path, text, problems=(Problem(Severity.ERROR, why,
                                                      SourceLocation(path, 1, 1)),))
    try:
        program = parse(text, path)
    except RecursionError:
        return Analysis(path, text, problems=(_too_deep(path),))
    except OrccadError as error:
        return Analysis(path, text, problems=tuple(problems_of(error)))
    try:
        source = check_source(path, text, program, host, read)
    except RecursionError:
        return Analysis(path, text, program, problems=(_too_deep(path),))
    except OrccadError as error:
        return Analysis(path, text, program, problems=tuple(problems_of(error)))
    return Analysis(path, text, source.program, source,
                    tuple(_warning(w) for w in source.warnings),
                    tuple(f.path for f in source.imported))


def _too_deep(path: str) -> Problem:
    return Problem(Severity.ERROR, "nested too deeply to analyse (see docs/limits.md)",
                   SourceLocation(path, 1, 1))
