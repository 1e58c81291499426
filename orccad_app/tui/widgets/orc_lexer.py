"""A Pygments lexer for the plan language (``.orc``), for the source view's highlighting."""

from __future__ import annotations

from pygments.lexer import RegexLexer, words
from pygments.token import Comment, Keyword, Name, Number, Operator, Punctuation, String, Text

__all__ = ["OrcLexer"]

_DECLARATIONS = ("robot", "robottask", "mission", "input", "output", "signal", "var", "module",
                 "connect", "exception", "law", "task_function", "duration", "precondition",
                 "postcondition", "property", "assume", "period", "wcet", "bcet", "priority")
_STATEMENTS = ("abort", "weak", "await", "immediate", "catch", "do", "each", "else", "emit",
               "every", "exit", "halt", "handle", "if", "loop", "nothing", "on", "par",
               "pause", "race", "repeat", "run", "suspend", "sustain", "trap", "try", "when",
               "within", "from", "measure", "adjust", "fatal", "always", "eventually", "never",
               "next", "once", "since", "until", "historically", "previously", "and", "or",
               "not")
_CONSTANTS = ("true", "false", "pi", "started", "ended", "raised", "active", "done", "failed",
              "aborted")


class OrcLexer(RegexLexer):
    """The plan language: declarations, statements, units, comments."""

    name = "ORCCAD plan"
    aliases = ["orc"]
    filenames = ["*.orc"]
    tokens = {
        "root": [
            (r"\s+", Text),
            (r"//.*?$", Comment.Single),
            (r"/\*(.|\n)*?\*/", Comment.Multiline),
            (r'"[^"]*"', String),
            (words(_DECLARATIONS, suffix=r"\b"), Keyword.Declaration),
            (words(_STATEMENTS, suffix=r"\b"), Keyword),
            (words(_CONSTANTS, suffix=r"\b"), Keyword.Constant),
            (r"\d+(\.\d*)?([eE][+-]?\d+)?\s*(ms|us|ns|s)\b", Number.Float),
            (r"\d+(\.\d*)?([eE][+-]?\d+)?", Number),
            (r"[A-Z][\w]*", Name.Class),
            (r"[a-z_][\w]*", Name),
            (r"->|:=|[-+*/<>=!?]+", Operator),
            (r"[{}()\[\];:,.|]", Punctuation),
        ],
    }
