"""What each name of a document stands for: the declarations of its AST, by scope, and the
resolution of a name (a token of the grammar's lexer) to the declaration it refers to.

Scopes, from the inside out: inside a Robot-Task, its parameters, Module-Tasks and
exceptions; inside a mission, its traps, variables and local signals (the nearest
declaration before the name), its own signals and signature; then the file: its signals,
Robot-Tasks, missions (imported ones included: they are declared in their own file), robots,
exceptions of every Robot-Task, properties. ``X.y`` resolves ``X`` (a module, a robot, a
mission) and leaves ``y``.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass
from typing import Any

from orccad_app.diagnostics import SourceLocation
from orccad_app.lang import ast
from orccad_app.lang.walk import nodes
from orccad_app.lsp.tokens import Tok

__all__ = ["DeclKind", "Declaration", "Index", "token_at"]


class DeclKind(str, enum.Enum):
    """What a declared name is."""

    ROBOT = "robot"
    ROBOTTASK = "robottask"
    MISSION = "mission"
    SIGNAL = "signal"
    VARIABLE = "variable"
    PARAMETER = "parameter"
    MODULE = "module"
    EXCEPTION = "exception"
    PROPERTY = "property"
    TRAP = "trap"


@dataclass(frozen=True)
class Declaration:
    """One declared name: its kind, the AST node that declares it and where (``node.loc``),
    and the Robot-Task or mission it belongs to (``None`` at file level)."""

    name: str
    kind: DeclKind
    node: Any
    owner: str | None = None

    @property
    def loc(self) -> SourceLocation:
        return self.node.loc

    @property
    def key(self) -> tuple:
        loc = self.loc
        return (self.kind, self.name, loc.file, loc.line, loc.col)


def token_at(toks: list[Tok], line: int, col: int) -> int | None:
    """The index of the token under 0-based ``line:col`` (a name touching the cursor wins
    over punctuation), or ``None``."""
    found = None
    for index, tok in enumerate(toks):
        if tok.line > line:
            break
        if tok.contains(line, col):
            if tok.kind == "NAME":
                return index
            found = index if found is None else found
    return found


def _within(loc: SourceLocation, line: int, col: int) -> bool:
    """Whether the 1-based ``line:col`` is inside ``loc`` (its end included)."""
    if loc.line <= 0:
        return False
    end = (loc.end_line or loc.line, loc.end_col or 10**9)
    return (loc.line, loc.col) <= (line, col) <= end


class Index:
    """The declarations of one parsed program, and name resolution over them."""

    def __init__(self, program: ast.Program) -> None:
        self.program = program
        self.globals: dict[str, list[Declaration]] = {}
        self.scopes: dict[tuple[str, str], list[Declaration]] = {}
        for signal in program.signals:
            self._add(self.globals, Declaration(signal.name, DeclKind.SIGNAL, signal))
        for task in program.robottasks:
            self._add(self.globals, Declaration(task.name, DeclKind.ROBOTTASK, task))
            self._task_scope(task)
        for mission in program.missions + program.imported_missions:
            self._add(self.globals, Declaration(mission.name, DeclKind.MISSION, mission))
        for mission in program.missions:
            self._mission_scope(mission)
        for robot in program.robots:
            self._add(self.globals, Declaration(robot.name, DeclKind.ROBOT, robot))
        for prop in program.properties:
            self._add(self.globals, Declaration(prop.name, DeclKind.PROPERTY, prop,
                                                prop.mission))

    @staticmethod
    def _add(table: dict[str, list[Declaration]], decl: Declaration) -> None:
        table.setdefault(decl.name, []).append(decl)

    def _task_scope(self, task: ast.RobotTask) -> None:
        scope: dict[str, list[Declaration]] = {}
        for param in task.params:
            self._add(scope, Declaration(param.name, DeclKind.PARAMETER, param, task.name))
        for module in task.modules:
            self._add(scope, Declaration(module.name, DeclKind.MODULE, module, task.name))
        for exception in task.exceptions:
            decl = Declaration(exception.name, DeclKind.EXCEPTION, exception, task.name)
            self._add(scope, decl)
            self._add(self.globals, decl)
        self.scopes[("robottask", task.name)] = [d for ds in scope.values() for d in ds]

    def _mission_scope(self, mission: ast.Mission) -> None:
        found = [Declaration(s.name, DeclKind.SIGNAL, s, mission.name)
                 for s in mission.signature + mission.signals]
        for node in nodes(mission):
            if isinstance(node, ast.LocalSignals):
                found += [Declaration(s.name, DeclKind.SIGNAL, s, mission.name)
                          for s in node.signals]
            elif isinstance(node, ast.VarDecl):
                found.append(Declaration(node.name, DeclKind.VARIABLE, node, mission.name))
            elif isinstance(node, ast.Trap):
                found.append(Declaration(node.name, DeclKind.TRAP, node, mission.name))
        self.scopes[("mission", mission.name)] = found

    # -- resolution --------------------------------------------------------------------

    def enclosing(self, line: int, col: int) -> Any:
        """The top-level item of this file around the 1-based ``line:col``, or ``None``."""
        for item in self.program.items:
            if _within(item.loc, line, col):
                return item
        return None

    def resolve(self, toks: list[Tok], index: int) -> Declaration | None:
        """The declaration the NAME token ``toks[index]`` refers to, or ``None``."""
        tok = toks[index]
        if tok.kind != "NAME":
            return None
        after_dot = index > 0 and toks[index - 1].kind == "DOT"
        item = self.enclosing(tok.line + 1, tok.col + 1)
        if after_dot:
            if isinstance(item, ast.Property) and index >= 2 \
                    and toks[index - 2].text == item.mission:
                return self._first(self.globals.get(tok.text, ()), DeclKind.PROPERTY)
            return None  # a port, a parameter, a field: not a declaration of this file
        if isinstance(item, ast.RobotTask):
            local = [d for d in self.scopes.get(("robottask", item.name), ())
                     if d.name == tok.text]
            if local:
                return local[0]
        if isinstance(item, ast.Mission):
            local = [d for d in self.scopes.get(("mission", item.name), ())
                     if d.name == tok.text]
            before = [d for d in local if (d.loc.line, d.loc.col) <= (tok.line + 1, tok.col + 1)]
            if before:
                return max(before, key=lambda d: (d.loc.line, d.loc.col))
            if local:
                return local[0]
        candidates = self.globals.get(tok.text, ())
        order = (DeclKind.SIGNAL, DeclKind.ROBOTTASK, DeclKind.MISSION, DeclKind.ROBOT,
                 DeclKind.EXCEPTION, DeclKind.PROPERTY)
        for kind in order:
            found = self._first(candidates, kind)
            if found is not None:
                return found
        return None

    @staticmethod
    def _first(candidates, kind: DeclKind) -> Declaration | None:
        return next((d for d in candidates if d.kind is kind), None)

    def references(self, toks: list[Tok], target: Declaration) -> list[int]:
        """The indices of the NAME tokens that resolve to ``target``."""
        return [i for i, tok in enumerate(toks)
                if tok.kind == "NAME" and tok.text == target.name
                and (found := self.resolve(toks, i)) is not None and found.key == target.key]
