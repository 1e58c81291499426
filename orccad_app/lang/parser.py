"""Parse plan-language text into the dataclass AST.

>>> program = parse("mission M { output O; emit O; }", "m.orc")
>>> program.missions[0].body.statements[0].signal
'O'

The grammar is ``plan.lark`` (package data), compiled once by lark's LALR(1) parser with the
contextual lexer, ``strict=True`` (no shift/reduce conflict, no terminal collision) and
``propagate_positions=True``. Every failure is an :class:`~orccad_app.diagnostics.OrccadError`
located at ``file:line:col`` (see :mod:`.syntax_errors`); no lark exception escapes.
"""

from __future__ import annotations

import functools
import hashlib
import importlib.resources
import os
import re
from pathlib import Path
from typing import Iterator

from lark import Lark, Token, Tree
from lark.exceptions import LarkError, UnexpectedInput, UnexpectedToken, VisitError
from lark.lexer import PatternStr

from orccad_app.diagnostics import OrccadError, SourceLocation
from orccad_app.lang import ast
from orccad_app.lang.limits import check_tree, ensure_recursion_headroom
from orccad_app.lang.syntax_errors import syntax_error
from orccad_app.lang.transform import ToAst

__all__ = ["parse", "keywords", "grammar_text", "grammar_lark", "lex", "parse_interactive",
           "literal_terminals"]

_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*\Z")


def grammar_text() -> str:
    """The text of ``plan.lark``."""
    return importlib.resources.files("orccad_app.lang").joinpath("plan.lark").read_text(
        encoding="utf-8")


def _cache_file(grammar: str) -> str | bool:
    """Where lark keeps the parse tables between runs: a private per-user cache file named
    after the grammar and lark's version (building the tables costs ~0.3 s per start-up);
    ``False`` (no cache) when the user's cache folder cannot be created."""
    import lark

    base = Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache") / "orccad"
    try:
        base.mkdir(mode=0o700, parents=True, exist_ok=True)
    except OSError:
        return False
    key = hashlib.sha256(f"{lark.__version__}\n{grammar}".encode()).hexdigest()[:24]
    return str(base / f"plan-lark-{key}.cache")


_OPTIONS = dict(parser="lalr", lexer="contextual", propagate_positions=True,
                maybe_placeholders=True)


def grammar_lark() -> Lark:
    """A freshly built parser, not from the disk cache: it keeps its grammar object, which
    grammar-driven tools need (``hypothesis.extra.lark.from_lark``)."""
    return Lark(grammar_text(), strict=True, **_OPTIONS)


@functools.lru_cache(maxsize=1)
def _lark() -> Lark:
    """The compiled parser (built once per process, its tables cached on disk)."""
    grammar = grammar_text()
    options = _OPTIONS
    cache = _cache_file(grammar)
    if cache:
        try:
            return Lark(grammar, strict=True, cache=cache, **options)
        except Exception:  # noqa: BLE001 - a corrupt or unreadable cache: build afresh
            try:
                os.unlink(cache)
            except OSError:
                pass
    try:
        return Lark(grammar, strict=True, **options)
    except LarkError as error:
        if "interegular" not in str(error):
            raise
        # strict mode's terminal-collision check needs the optional `interegular` package;
        # the grammar is verified in strict mode by the test suite, so run without it.
        return Lark(grammar, **options)  # pragma: no cover


@functools.lru_cache(maxsize=1)
def keywords() -> frozenset[str]:
    """The reserved words: every literal of the grammar that looks like an identifier."""
    return frozenset(
        t.pattern.value for t in _lark().terminals
        if isinstance(t.pattern, PatternStr) and _NAME.match(t.pattern.value))


@functools.lru_cache(maxsize=1)
def _lexer():
    """The grammar's terminals as one standalone lexer (no parser states: every terminal
    everywhere), built once; for tools that read a text that may not parse."""
    return _lark()._build_lexer()


def lex(text: str) -> Iterator[Token]:
    """The tokens of ``text`` by the grammar's own terminals, comments and blanks skipped,
    without parsing (editor tools: outline, folding, names under the cursor of a file with
    a syntax error). Raises lark's ``UnexpectedCharacters`` at a character no terminal
    matches, after the tokens before it."""
    from lark.lexer import LexerThread
    return LexerThread.from_text(_lexer(), text).lex(None)


def parse_interactive(text: str):
    """lark's interactive parser over ``text`` (its ``accepts()`` is the set of terminals the
    grammar takes next): for completion."""
    return _lark().parse_interactive(text)


@functools.lru_cache(maxsize=1)
def literal_terminals() -> dict[str, str]:
    """Terminal name → its literal text, for every terminal that is a fixed string
    (keywords and punctuation: ``MISSION`` → ``mission``, ``LBRACE`` → ``{``)."""
    return {t.name: t.pattern.value for t in _lark().terminals
            if isinstance(t.pattern, PatternStr)}


def _reserved_name(tree: Tree, filename: str) -> OrccadError | None:
    """An error for the first keyword used as an identifier, if any.

    The contextual lexer reads a keyword as ``NAME`` where no keyword fits (``emit loop;``);
    keywords are reserved, so such a token is an error — except as the name of a named
    argument, where nothing else can stand: ``min_jerk(goal = g, duration = 1.0)``.
    """
    reserved = keywords()
    bad = [child for subtree in tree.iter_subtrees()
           for index, child in enumerate(subtree.children)
           if isinstance(child, Token) and child.type == "NAME" and str(child) in reserved
           and not (subtree.data == "named_arg" and index == 0)]
    if not bad:
        return None
    token = min(bad, key=lambda t: (t.line, t.column))
    location = SourceLocation(filename, token.line, token.column, token.end_line,
                              token.end_column)
    return OrccadError(f"'{token}' is a reserved keyword and cannot be used as a name",
                       location)


def _accepts(error: UnexpectedInput, text: str) -> set[str] | None:
    """The terminals the parser could really take where ``error`` happened.

    lark's ``expected`` is the lexer's set when the contextual lexer found no token fitting
    the state; replaying the input in an interactive parser gives the parser's own set.
    """
    if not isinstance(error, UnexpectedToken):
        return None
    if error.interactive_parser is not None:
        return set(error.accepts)
    replay = _lark().parse_interactive(text)
    try:
        replay.exhaust_lexer()
    except UnexpectedInput:
        return set(replay.accepts())
    return None  # pragma: no cover - the replay fails where the parse did


def parse(text: str, filename: str = "<input>") -> ast.Program:
    """Parse the text of one ``.orc`` file.

    Raises :class:`OrccadError` (with a location) on any lexical or syntax error, a
    reserved keyword used as a name, an unknown protocol, a duplicate Robot-Task item, a
    duration that is not whole nanoseconds, a literal or a nesting outside the language's
    limits (:mod:`.limits`). A leading byte-order mark is ignored.
    """
    if text.startswith("\ufeff"):
        text = text[1:]
    ensure_recursion_headroom()
    return _parse(text, filename)


#: Parsed texts kept (the AST is immutable, so a repeated parse of the same text, such as
#: the libraries a file imports, re-analysed at each keystroke by the language server,
#: returns the same tree); errors are not kept.
PARSE_CACHE_SIZE = 16


@functools.lru_cache(maxsize=PARSE_CACHE_SIZE)
def _parse(text: str, filename: str) -> ast.Program:
    try:
        tree = _lark().parse(text)
    except UnexpectedInput as error:
        terminals = {t.name: t for t in _lark().terminals}
        raise syntax_error(error, text, filename, keywords(), terminals,
                           _accepts(error, text)) from None
    problem = _reserved_name(tree, filename)
    if problem is not None:
        raise problem
    check_tree(tree, filename)
    try:
        return ToAst(filename).transform(tree)
    except VisitError as error:
        if isinstance(error.orig_exc, (OrccadError, RecursionError)):
            raise error.orig_exc from None
        raise
