"""The plan language front end: grammar, AST, parser, name checking.

- :func:`parse` ``(text, filename) -> ast.Program`` (syntax errors: located ``OrccadError``);
- :func:`check` ``(program) -> CheckResult``: names, scopes, each mission's interface and the
  signal/data kind of every condition; :func:`diagnose` lists the errors without raising;
- :mod:`orccad_app.lang.ast`: the dataclass AST.

Names are imported lazily, so ``import orccad_app.lang.ast`` does not load lark.
"""

from __future__ import annotations

import importlib

__all__ = ["ast", "parse", "keywords", "check", "diagnose", "CheckResult",
           "MissionInterface", "NameKind", "ConditionKind", "classify_condition"]

_HOMES = {
    "ast": "orccad_app.lang.ast",
    "parse": "orccad_app.lang.parser", "keywords": "orccad_app.lang.parser",
    "check": "orccad_app.lang.names", "diagnose": "orccad_app.lang.names",
    "CheckResult": "orccad_app.lang.names", "MissionInterface": "orccad_app.lang.names",
    "NameKind": "orccad_app.lang.scope", "ConditionKind": "orccad_app.lang.scope",
    "classify_condition": "orccad_app.lang.scope",
}


def __getattr__(name: str):
    if name not in _HOMES:
        raise AttributeError(f"module 'orccad_app.lang' has no attribute {name!r}")
    module = importlib.import_module(_HOMES[name])
    return module if name == "ast" else getattr(module, name)


def __dir__() -> list[str]:
    return sorted(__all__)
