"""The plan language front end: grammar, AST, parser, name checking.

``parse(text, filename)`` gives a :class:`~orccad_app.lang.ast.Program`;
``check(program)`` resolves names and returns each mission's interface.
"""

from __future__ import annotations

__all__: list[str] = []
