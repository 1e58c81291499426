"""Friendly, located messages for syntax errors.

:func:`syntax_error` turns a lark :class:`~lark.exceptions.UnexpectedInput` into an
:class:`~orccad_app.diagnostics.OrccadError` by looking at the offending token, the token
before it and what the parser expected. The usual mistakes get named messages:

- a missing ``;`` → ``expected ';' after statement`` at the end of the statement;
- an unclosed ``{`` → ``unclosed '{'`` at that brace; a stray ``}`` → ``unmatched '}'``;
- a misspelt keyword or statement → ``unknown keyword 'mision'; did you mean 'mission'?``;
- end of input → ``unexpected end of file``;
- ``2 sec`` where a duration is expected → ``bad duration unit 'sec'``;
- an unterminated string or ``/* comment``.
"""

from __future__ import annotations

import difflib
import re
from dataclasses import dataclass

from lark.exceptions import UnexpectedCharacters, UnexpectedInput, UnexpectedToken
from lark.lexer import PatternStr

from orccad_app.diagnostics import OrccadError, SourceLocation

__all__ = ["syntax_error", "UNITS"]

#: Duration units, for messages.
UNITS = ("s", "ms", "us", "ns")

_SCAN = re.compile(r'''(?P<str>"(?:[^"\\\n]|\\.)*"?)
                     |(?P<com>//[^\n]*|/\*(?:.|\n)*?(?:\*/|\Z))
                     |(?P<ws>\s+)
                     |(?P<num>\d+(?:\.\d+)?(?:[eE][-+]?\d+)?)
                     |(?P<word>[A-Za-z_][A-Za-z0-9_]*)
                     |(?P<op>:=|->|<->|\|\||<=|>=|==|!=|.)''', re.VERBOSE)

#: Words that begin a declaration (rather than a statement), for the ';' message.
_DECLARATION_WORDS = frozenset({
    "robot", "input", "output", "property", "assume", "duration", "task_function", "law",
    "module", "connect", "precondition", "exception", "postcondition", "var"})

_TERMINAL_WORDS = {
    "NAME": "a name", "INT": "an integer", "FLOAT": "a number", "DURATION": "a duration",
    "STRING": "a string", "PROTOCOL": "a protocol", "$END": "end of file",
    "IMMEDIATE": "'immediate'", "WEAK": "'weak'",
}


#: Terminals that start an expression, or continue one: left out of "expected ..." lists.
_EXPRESSION_START = frozenset({"NAME", "INT", "FLOAT", "DURATION", "STRING", "LSQB", "LPAR",
                               "QMARK", "MINUS", "NOT", "TRUE", "FALSE", "PI", "PRE"})
_OPERATORS = frozenset({"+", "-", "*", "/", "<", "<=", ">", ">=", "==", "!=", "and", "or"})


@dataclass(frozen=True)
class _Tok:
    kind: str
    text: str
    start: int
    end: int


def _tokens(text: str, stop: int) -> list[_Tok]:
    """Rough tokens of ``text[:stop]``, comments and whitespace dropped."""
    found = []
    for match in _SCAN.finditer(text, 0, stop):
        kind = match.lastgroup
        if kind not in ("ws", "com"):
            found.append(_Tok(kind, match.group(), match.start(), match.end()))
    return found


class _Locator:
    """Offsets ↔ 1-based line/column in one text."""

    def __init__(self, text: str, filename: str):
        self.text, self.filename = text, filename

    def at(self, start: int, end: int | None = None) -> SourceLocation:
        line = self.text.count("\n", 0, start) + 1
        col = start - (self.text.rfind("\n", 0, start) + 1) + 1
        if end is None or "\n" in self.text[start:end]:
            return SourceLocation(self.filename, line, col)
        return SourceLocation(self.filename, line, col, line, col + (end - start))

    def end_of(self, tok: _Tok) -> SourceLocation:
        """The position just after ``tok``."""
        return self.at(tok.end)

    def offset(self, line: int, column: int) -> int:
        start = 0
        for _ in range(line - 1):
            start = self.text.index("\n", start) + 1
        return start + column - 1


def _unclosed_brace(tokens: list[_Tok]) -> _Tok | None:
    """The innermost ``{`` still open after ``tokens``, if any."""
    stack: list[_Tok] = []
    for tok in tokens:
        if tok.text == "{":
            stack.append(tok)
        elif tok.text == "}" and stack:
            stack.pop()
    return stack[-1] if stack else None


def _describe(expected: set[str], lark_terminals: dict) -> list[str]:
    words = []
    if {"NAME", "INT", "FLOAT"} <= expected:
        words.append("an expression")
        expected = expected - _EXPRESSION_START
    for name in sorted(expected):
        pattern = getattr(lark_terminals.get(name), "pattern", None)
        if name in _TERMINAL_WORDS:
            words.append(_TERMINAL_WORDS[name])
        elif isinstance(pattern, PatternStr):
            if pattern.value not in _OPERATORS:
                words.append(f"'{pattern.value}'")
        else:
            words.append(name)
    return sorted(set(words))


def _suggest(word: str, candidates, cutoff: float = 0.6) -> str:
    close = difflib.get_close_matches(word, sorted(candidates), n=1, cutoff=cutoff)
    return f"; did you mean '{close[0]}'?" if close else ""


def _statement_kind(tokens: list[_Tok]) -> str:
    """'declaration' or 'statement': what the tokens before an error are in."""
    for index in range(len(tokens) - 1, -1, -1):
        if tokens[index].text in (";", "{", "}"):
            first = tokens[index + 1] if index + 1 < len(tokens) else None
            break
    else:
        first = tokens[0] if tokens else None
    if first is not None and first.text in _DECLARATION_WORDS:
        return "declaration"
    return "statement"


def _in_signal_declaration(tokens: list[_Tok]) -> bool:
    """Whether the tokens end inside ``input``/``output``/``signal`` declarations."""
    for tok in reversed(tokens):
        if tok.text in (";", "{", "}"):
            return False
        if tok.text in ("input", "output", "signal"):
            return True
    return False


def _characters_error(error: UnexpectedCharacters, loc: _Locator) -> OrccadError:
    pos = error.pos_in_stream
    rest = loc.text[pos:]
    if rest.startswith('"'):
        return OrccadError("unterminated string", loc.at(pos, pos + 1))
    if rest.startswith("/*"):
        return OrccadError("unterminated comment: '/*' has no matching '*/'",
                           loc.at(pos, pos + 2))
    return OrccadError(f"unexpected character {rest[:1]!r}", loc.at(pos, pos + 1))


def _token_error(error: UnexpectedToken, loc: _Locator, keywords: frozenset[str],
                 terminals: dict, accepts: set[str]) -> OrccadError:
    token = error.token
    at_end = token.type == "$END"
    pos = len(loc.text) if at_end else loc.offset(token.line, token.column)
    before = _tokens(loc.text, pos)
    prev = before[-1] if before else None
    here = None if at_end else loc.at(pos, pos + len(str(token)))
    found = "end of file" if at_end else f"'{token}'"
    texts = _expected_texts(accepts, terminals)

    unclosed = _unclosed_brace(before)
    if unclosed is not None and (at_end or str(token) in _TOP_LEVEL
                                 or (prev is not None and prev.text in _TOP_LEVEL)):
        return OrccadError("unclosed '{': no matching '}' before " + found,
                           loc.at(unclosed.start, unclosed.end))
    if at_end:
        return OrccadError("unexpected end of file" + _expecting(accepts, terminals),
                           loc.end_of(prev) if prev else loc.at(0))
    if loc.text.startswith("/*", pos):
        return OrccadError("unterminated comment: '/*' has no matching '*/'",
                           loc.at(pos, pos + 2))
    if str(token) == "}" and unclosed is None:
        return OrccadError("unmatched '}'", here)
    if "DURATION" in accepts and token.type in ("INT", "FLOAT"):
        return _duration_error(token, pos, loc)
    if token.type == "NAME" and prev is not None and prev.kind == "num":
        return OrccadError(f"bad duration unit '{token}' (expected one of "
                           f"{', '.join(UNITS)})", here)
    if prev is not None and prev.kind == "word" and ":=" in texts \
            and not _in_signal_declaration(before):  # `output O := 0;` is fine
        return _unknown_statement(prev, loc, keywords)
    if (prev is not None and prev.kind == "word" and prev.text not in keywords
            and token.type in ("NAME", "LPAR")):
        hint = _suggest(prev.text, keywords, cutoff=0.8)
        if hint:
            return OrccadError(f"unknown keyword '{prev.text}'{hint}",
                               loc.at(prev.start, prev.end))
    if "SEMICOLON" in accepts and prev is not None:
        return OrccadError(f"expected ';' after {_statement_kind(before)}", loc.end_of(prev))
    if token.type == "NAME":
        choices = (texts & keywords) or keywords
        hint = _suggest(str(token), choices)
        if hint:
            return OrccadError(f"unknown keyword '{token}'{hint}", here)
    return OrccadError(f"unexpected {found}" + _expecting(accepts, terminals), here)


_TOP_LEVEL = frozenset({"mission", "robottask", "robot", "property", "assume"})


def _line_of(loc: _Locator, tok: _Tok) -> int:
    return loc.text.count("\n", 0, tok.end) + 1


def _expected_texts(expected: set[str], terminals: dict) -> set[str]:
    return {w.strip("'") for w in _describe(expected, terminals)}


def _expecting(expected: set[str], terminals: dict) -> str:
    words = _describe(expected, terminals)
    if not words or len(words) > 8:
        return ""
    return "; expected " + (words[0] if len(words) == 1 else
                            ", ".join(words[:-1]) + " or " + words[-1])


def _duration_error(token, pos: int, loc: _Locator) -> OrccadError:
    match = re.compile(r"[ \t]*([A-Za-z_]\w*)").match(loc.text, pos + len(str(token)))
    if match:
        start = match.start(1)
        return OrccadError(f"bad duration unit '{match.group(1)}' (expected one of "
                           f"{', '.join(UNITS)})", loc.at(start, match.end(1)))
    return OrccadError(f"expected a duration after '{token}' (a number and a unit: "
                       f"{', '.join(UNITS)})", loc.at(pos, pos + len(str(token))))


def _unknown_statement(prev: _Tok, loc: _Locator, keywords: frozenset[str]) -> OrccadError:
    where = loc.at(prev.start, prev.end)
    if prev.text in keywords:
        return OrccadError(f"'{prev.text}' cannot start a statement here", where)
    hint = _suggest(prev.text, keywords)
    return OrccadError(f"unknown statement '{prev.text}'{hint}", where)


def syntax_error(error: UnexpectedInput, text: str, filename: str, keywords: frozenset[str],
                 terminals: dict | None = None,
                 accepts: set[str] | None = None) -> OrccadError:
    """The located :class:`OrccadError` for a lark parse failure.

    ``terminals`` maps terminal names to lark definitions (to spell expected tokens);
    ``accepts`` is the exact set of terminals the parser could take at the failure
    (``error.expected`` when not given).
    """
    loc = _Locator(text, filename)
    if isinstance(error, UnexpectedCharacters):
        return _characters_error(error, loc)
    if isinstance(error, UnexpectedToken):
        accepts = set(error.expected if accepts is None else accepts)
        return _token_error(error, loc, keywords, terminals or {}, accepts)
    return OrccadError("syntax error", loc.at(getattr(error, "pos_in_stream", 0) or 0))
