"""Imports: missions of another file, ``from "lib/homing.orc" import Homing;``.

>>> files = {"lib/h.orc": "mission Hello [output Hi] { emit Hi; }"}
>>> program = parse('from "lib/h.orc" import Hello;\\nmission M { output Hi; '
...                 'run mission Hello; }', "m.orc")
>>> merged, loaded = resolve_imports(program, lambda path: files[path])
>>> [m.name for m in merged.imported_missions], [f.path for f in loaded]
(['Hello'], ['lib/h.orc'])

The path is resolved relative to the importing file's folder. The imported file is parsed and
name-checked on its own (its errors are located in it, with a note at the ``import``), its own
imports resolved first. An imported mission comes with what it needs from its file: the
missions it runs (``run mission``), the Robot-Tasks it runs and the robots those run on; all
of it goes into :attr:`~orccad_app.lang.ast.Program.library` of the importer, one namespace:

- a mission or Robot-Task of the importer (or of another import) with the same name as one
  an import brings is a clash (the same declaration reached twice, through two imports, is
  not);
- a robot the importer declares too must be the same robot (same type and arguments);
- an imported mission sees only its own signals (its ``[signature]`` and declarations): one
  that uses a file-level signal of its file is refused;
- only missions can be named in an ``import``.

Budgets (docs/limits.md): imports nest at most :data:`MAX_IMPORT_DEPTH` files deep and one
program loads at most :data:`MAX_IMPORTED_FILES` files; a cycle is an error.
"""

from __future__ import annotations

import os
from dataclasses import dataclass, fields, is_dataclass, replace
from typing import Any, Callable

from orccad_app.diagnostics import Diagnostic, OrccadError, SourceLocation
from orccad_app.lang import ast
from orccad_app.lang.names import diagnose
from orccad_app.lang.parser import parse
from orccad_app.lang.walk import nodes

__all__ = ["ImportedFile", "resolve_imports", "MAX_IMPORT_DEPTH", "MAX_IMPORTED_FILES"]

#: Deepest chain of imports (a file importing a file importing …), the importer excluded.
MAX_IMPORT_DEPTH = 16
#: Most files one program loads through its imports (each counted once).
MAX_IMPORTED_FILES = 64


@dataclass(frozen=True)
class ImportedFile:
    """A file loaded by an ``import``: its path (as its locations name it) and its text."""

    path: str
    text: str


Reader = Callable[[str], str]


def resolve_imports(program: ast.Program,
                    read: Reader) -> tuple[ast.Program, tuple[ImportedFile, ...]]:
    """``program`` with its :attr:`~ast.Program.library` filled, and every file loaded (in
    load order: what a digest of the program must cover). ``read(path)`` returns a file's
    text or raises :class:`OrccadError`."""
    if not program.imports:
        return program, ()
    resolver = _Resolver(read)
    merged = resolver.resolve(program, (_key(program.filename),))
    return merged, tuple(resolver.files.values())


def _key(path: str) -> str:
    return os.path.realpath(path)


def _display(chain: tuple[str, ...]) -> str:
    return " -> ".join(os.path.relpath(p) for p in chain)


def _imported_here(imp: ast.Import) -> Diagnostic:
    return Diagnostic("note", f'imported here (from "{imp.path}")', imp.loc)


class _Resolver:
    """One program's imports: each file loaded, parsed and checked once."""

    def __init__(self, read: Reader) -> None:
        self.read = read
        self.files: dict[str, ImportedFile] = {}
        self.programs: dict[str, ast.Program] = {}

    def resolve(self, program: ast.Program, chain: tuple[str, ...]) -> ast.Program:
        merger = _Merger(program)
        for imp in program.imports:
            library = self._load(imp, program.filename, chain)
            for name in imp.names:
                mission = _mission(library, name)
                needed = _needed(library, mission)
                _own_signals_only(library, mission, needed, imp)
                merger.add(needed, imp, name)
        return replace(program, library=tuple(merger.items))

    def _load(self, imp: ast.Import, importer: str, chain: tuple[str, ...]) -> ast.Program:
        if "\0" in imp.path:
            raise OrccadError(f'cannot import "{imp.path!r}": a file name cannot contain a NUL '
                              "character", imp.path_loc)
        path = os.path.normpath(os.path.join(os.path.dirname(importer), imp.path))
        key = _key(path)
        if key in chain:
            raise OrccadError(f"import cycle: {_display((*chain, key))}", imp.path_loc)
        if len(chain) > MAX_IMPORT_DEPTH:
            raise OrccadError(f"imports nest deeper than {MAX_IMPORT_DEPTH} files (see "
                              "docs/limits.md)", imp.path_loc)
        if key in self.programs:
            return self.programs[key]
        if len(self.files) >= MAX_IMPORTED_FILES:
            raise OrccadError(f"more than {MAX_IMPORTED_FILES} files imported (see "
                              "docs/limits.md)", imp.path_loc)
        try:
            text = self.read(path)
        except OrccadError as error:
            if error.location is not None:
                raise OrccadError(error.message, error.location,
                                  (*error.notes, _imported_here(imp))) from None
            raise OrccadError(f'cannot import "{imp.path}": {error.message}',
                              imp.path_loc) from None
        self.files[key] = ImportedFile(path, text)
        try:
            library = self.resolve(parse(text, path), (*chain, key))
            problems = diagnose(library)
        except OrccadError as error:
            raise OrccadError(error.message, error.location,
                              (*error.notes, _imported_here(imp))) from None
        if problems:
            first = problems[0]
            raise OrccadError(first.message, first.location,
                              (*first.notes, _imported_here(imp)))
        self.programs[key] = library
        return library


def _mission(library: ast.Program, name: ast.ImportedName) -> ast.Mission:
    """The mission ``name`` of ``library``; an error when it is something else or nothing."""
    mission = library.mission(name.name)
    if mission is not None:
        return mission
    kinds = [("a Robot-Task", library.robottasks), ("a robot", library.robots),
             ("a signal", library.signals), ("a property", library.properties)]
    for what, items in kinds:
        item = next((i for i in items if i.name == name.name), None)
        if item is not None:
            raise OrccadError(
                f"'{name.name}' is {what} of {library.filename}, not a mission: only missions "
                "can be imported (the Robot-Tasks a mission runs come with it)", name.loc,
                (Diagnostic("note", "declared here", item.loc),))
    known = ", ".join(m.name for m in library.missions + library.imported_missions) or "none"
    raise OrccadError(f"{library.filename} has no mission '{name.name}' (its missions: "
                      f"{known})", name.loc)


def _needed(library: ast.Program, mission: ast.Mission) -> list:
    """``mission`` and what it needs from ``library``: the missions it runs (transitively),
    the Robot-Tasks run and their robots, in a deterministic order."""
    found: dict[tuple[str, str], Any] = {}
    stack = [mission]
    while stack:
        current = stack.pop()
        if ("mission", current.name) in found:
            continue
        found[("mission", current.name)] = current
        for node in nodes(current):
            if isinstance(node, ast.RunMission):
                target = library.mission(node.mission)
                if target is not None:
                    stack.append(target)
            elif isinstance(node, ast.Run):
                task = library.robottask(node.task)
                if task is not None and ("robottask", task.name) not in found:
                    found[("robottask", task.name)] = task
                    robot = next((r for r in library.robots if r.name == task.robot), None)
                    if robot is not None:
                        found[("robot", robot.name)] = robot
    return list(found.values())


def _own_signals_only(library: ast.Program, mission: ast.Mission, needed: list,
                      imp: ast.Import) -> None:
    """Refuse an imported mission that uses a file-level signal of its file."""
    if not library.signals:
        return
    alone = ast.Program(filename=library.filename, items=tuple(needed))
    problems = diagnose(alone)
    if problems:
        first = problems[0]
        raise OrccadError(
            f"{first.message}: mission '{mission.name}' is imported, and an imported mission "
            "sees only its own signals (its [signature] and declarations), not the "
            f"file-level ones of {library.filename}", first.location, (_imported_here(imp),))


def _same(a: Any, b: Any) -> bool:
    """Equal declarations, wherever they are written (locations ignored)."""
    if isinstance(a, SourceLocation) and isinstance(b, SourceLocation):
        return True
    if is_dataclass(a) and not isinstance(a, type):
        return type(a) is type(b) and all(_same(getattr(a, f.name), getattr(b, f.name))
                                          for f in fields(a))
    if isinstance(a, tuple) and isinstance(b, tuple):
        return len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b))
    return bool(a == b)


_KINDS = {ast.Mission: "mission", ast.RobotTask: "Robot-Task", ast.Robot: "robot"}


class _Merger:
    """The importer's library, built import by import, with the clash checks."""

    def __init__(self, program: ast.Program) -> None:
        self.items: list = []
        self.seen: dict[tuple[str, str], Any] = {}
        for item in program.items:
            if type(item) in _KINDS:
                self.seen[(_KINDS[type(item)], item.name)] = item
        self.filename = program.filename

    def add(self, needed: list, imp: ast.Import, name: ast.ImportedName) -> None:
        for item in needed:
            kind = _KINDS[type(item)]
            first = self.seen.get((kind, item.name))
            if first is None:
                self.seen[(kind, item.name)] = item
                self.items.append(item)
            elif first != item and not (kind == "robot" and _same(first, item)):
                raise self._clash(kind, item, first, imp, name)

    def _clash(self, kind: str, item: Any, first: Any, imp: ast.Import,
               name: ast.ImportedName) -> OrccadError:
        where = "this file" if first.loc.file == self.filename else first.loc.file
        notes = (Diagnostic("note", f"the {kind} of {where}", first.loc),
                 Diagnostic("note", f"the imported {kind}", item.loc))
        if kind == "robot":
            return OrccadError(f"robot '{item.name}' of {item.loc.file} (used by imported "
                               f"mission '{name.name}') differs from the robot '{item.name}' "
                               f"of {where}", name.loc, notes)
        brought = ("" if kind == "mission" and item.name == name.name
                   else f" (it comes with mission '{name.name}')")
        return OrccadError(f"{kind} '{item.name}' imported from {imp.path}{brought} clashes "
                           f"with the {kind} '{item.name}' of {where}", name.loc, notes)
