"""The budget of sub-mission inlining: ``run mission M`` copies M's body into the caller, so
the size of a mission once inlined is counted, from the source, before the lowering builds it.
"""

from __future__ import annotations

from orccad_app.lang import ast
from orccad_app.lang.walk import nodes

__all__ = ["MAX_INLINED_NODES", "inlined_size"]

MAX_INLINED_NODES = 200_000
"""Most syntax nodes a mission may have once its sub-missions are inlined (``run mission``
copies the sub-mission's body): sub-missions that run each other twice or ten times expand
2 kB of source to 10⁶–10⁹ copies; the expansion is counted before it is built."""


def inlined_size(program: ast.Program, mission: ast.Mission, limit: int = MAX_INLINED_NODES
                 ) -> int:
    """The syntax nodes of ``mission`` with every ``run mission`` replaced by the sub-mission's
    (counted once per mission, in time linear in the source; a cycle is left to the lowering,
    which reports it). The count stops growing past ``limit``."""
    sizes: dict[str, int] = {}

    def size(target: ast.Mission, stack: tuple[str, ...]) -> int:
        if target.name in sizes:
            return sizes[target.name]
        total = 0
        for node in nodes(target):
            total += 1
            if isinstance(node, ast.RunMission):
                inner = program.mission(node.mission)
                if inner is not None and inner.name not in stack:
                    total += size(inner, (*stack, inner.name))
            if total > limit:
                break
        sizes[target.name] = total
        return total

    return size(mission, (mission.name,))

