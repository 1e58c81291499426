"""The plan language front end: grammar, AST, parser, name checking.

- :func:`parse` ``(text, filename) -> ast.Program`` (syntax errors: located ``OrccadError``);
- :func:`check` ``(program) -> CheckResult``: names, scopes, each mission's interface and the
  signal/data kind of every condition;
- :mod:`orccad_app.lang.ast`: the dataclass AST.
"""

from __future__ import annotations

from orccad_app.lang import ast
from orccad_app.lang.names import (CheckResult, ConditionKind, MissionInterface, NameKind,
                                   check, classify_condition, diagnose)
from orccad_app.lang.parser import keywords, parse

__all__ = ["ast", "parse", "keywords", "check", "diagnose", "CheckResult",
           "MissionInterface", "NameKind", "ConditionKind", "classify_condition"]
