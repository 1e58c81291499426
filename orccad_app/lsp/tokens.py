"""The tokens of a document by the grammar's own lexer, even when it does not lex cleanly,
and what the editor tools read from them: brace pairs, the declaration a token opens.

A character no terminal matches (``$``, a stray quote) is skipped and lexing resumes after
it, at most :data:`MAX_SKIPS` times, so a broken document still gets an outline, folding and
names under the cursor.
"""

from __future__ import annotations

from dataclasses import dataclass

from lark.exceptions import UnexpectedInput

from orccad_app.lang.parser import lex

__all__ = ["Tok", "tokens", "brace_pairs", "MAX_SKIPS"]

#: Characters skipped in one document before lexing gives up on the rest.
MAX_SKIPS = 64


@dataclass(frozen=True, slots=True)
class Tok:
    """One token: its terminal ``kind`` (``NAME``, ``MISSION``, ``LBRACE``…), its text, and
    its position (0-based line and character column; ``end_col`` exclusive)."""

    kind: str
    text: str
    line: int
    col: int
    end_line: int
    end_col: int
    offset: int

    def contains(self, line: int, col: int) -> bool:
        """Whether the 0-based ``line:col`` is on this token (its end included)."""
        return (self.line, self.col) <= (line, col) <= (self.end_line, self.end_col)


def tokens(text: str) -> list[Tok]:
    """Every token of ``text`` (see the module's docstring); linear in the text's size."""
    out: list[Tok] = []
    start, skips = 0, 0
    while start <= len(text):
        line0 = text.count("\n", 0, start)
        col0 = start - (text.rfind("\n", 0, start) + 1)
        try:
            for token in lex(text[start:]):
                out.append(_tok(token, start, line0, col0))
            return out
        except UnexpectedInput as error:
            position = getattr(error, "pos_in_stream", None)
            skips += 1
            if position is None or skips > MAX_SKIPS:
                return out
            start += position + 1  # skip the character no terminal matches
    return out


def _tok(token, start: int, line0: int, col0: int) -> Tok:
    """A token of ``text[start:]`` placed in ``text``."""
    line, end_line = token.line - 1, token.end_line - 1
    col = token.column - 1 + (col0 if line == 0 else 0)
    end_col = token.end_column - 1 + (col0 if end_line == 0 else 0)
    return Tok(token.type, str(token), line + line0, col, end_line + line0, end_col,
               token.start_pos + start)


def brace_pairs(toks: list[Tok]) -> list[tuple[Tok, Tok | None]]:
    """Each ``{`` with its matching ``}`` (``None`` when unclosed), in opening order."""
    pairs: list[tuple[Tok, Tok | None]] = []
    stack: list[int] = []
    for tok in toks:
        if tok.kind == "LBRACE":
            stack.append(len(pairs))
            pairs.append((tok, None))
        elif tok.kind == "RBRACE" and stack:
            index = stack.pop()
            pairs[index] = (pairs[index][0], tok)
    return pairs
