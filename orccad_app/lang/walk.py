"""Walking the AST: every node of a tree, and the ``run`` statements in it.

Shared by the name checker (exceptions a ``try`` can catch), the Robot-Task checks (one
instantiation per ``run``) and the resource-conflict check (``run`` s of parallel branches).
"""

from __future__ import annotations

from typing import Iterator

from orccad_app.diagnostics import SourceLocation
from orccad_app.lang import ast

__all__ = ["nodes", "runs"]


def nodes(node) -> Iterator:
    """``node`` and every AST node below it, depth first, in source order."""
    yield node
    for name in getattr(node, "__dataclass_fields__", ()):
        value = getattr(node, name)
        for item in value if isinstance(value, tuple) else (value,):
            if hasattr(item, "__dataclass_fields__") and not isinstance(item, SourceLocation):
                yield from nodes(item)


def runs(node) -> Iterator[ast.Run]:
    """Every ``run`` statement in ``node`` (a statement, block, mission…), in source order."""
    return (n for n in nodes(node) if isinstance(n, ast.Run))
