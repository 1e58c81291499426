"""Name checking of a parsed file, and what the compiler needs from it.

>>> from orccad_app.lang import parse, check
>>> result = check(parse("mission M { input A; output O; await A; emit O; }", "m.orc"))
>>> [s.name for s in result.interface("M").inputs]
['A']

:func:`check` reports every error at once: it raises the first as an
:class:`~orccad_app.diagnostics.OrccadError` carrying the others as notes. Checked:

- undeclared signals (``emit``/``sustain``/``await``/``if``/``when``/``each``/``every``/
  ``?S``) and variables; emitting an input; ``emit S(v)`` on a pure signal and ``emit S`` on
  a valued one; assigning a signal; a signal used as a value (``S + 1``, write ``?S``);
  a condition mixing presence and data;
- duplicate declarations (signals of a scope, ``var`` of a block, robots, Robot-Tasks,
  missions, parameters, modules, exceptions, properties) with a note at the first one;
- ``exit T`` outside a trap ``T``; unknown types;
- unknown Robot-Task, parameter or missing argument in ``run`` and a ``catch`` of an
  exception no ``run`` in the ``try`` can raise (when Robot-Tasks are known: the file's plus
  ``tasks``; with none at all, ``run`` is not checked);
- Robot-Tasks: unknown robot, module in ``connect``/``adjust``, names not parameters;
- properties and assumptions naming an unknown mission, signal, Robot-Task or exception.

Scoping: file-level ``input``/``output`` are visible in every mission, a mission's own in
that mission; ``signal S { ... }`` declares locals for its body; ``var`` lasts to the end of
its enclosing block. A name may be redeclared in an inner scope only with the same kind.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Iterable, Mapping

from orccad_app.diagnostics import OrccadError
from orccad_app.lang import ast
from orccad_app.lang.declarations import (check_formula, check_robottask, check_type,
                                          check_unique)
from orccad_app.lang.mission_check import MissionChecker
from orccad_app.lang.scope import (Binding, ConditionKind, NameKind, Problems, Scope,
                                   classify_condition)

__all__ = ["check", "diagnose", "CheckResult", "MissionInterface", "NameKind", "ConditionKind",
           "classify_condition"]


@dataclass(frozen=True)
class MissionInterface:
    """The signals a mission exchanges with its environment, in declaration order.

    File-level declarations are included: they are visible in every mission.
    """

    name: str
    inputs: tuple[ast.SignalDecl, ...]
    outputs: tuple[ast.SignalDecl, ...]

    def signal(self, name: str) -> ast.SignalDecl | None:
        """The input or output called ``name``, or ``None``."""
        return next((s for s in self.inputs + self.outputs if s.name == name), None)


@dataclass(frozen=True)
class CheckResult:
    """What :func:`check` found in a file that passed.

    ``name_kinds`` maps every identifier (:class:`~.ast.Name` node) of a mission condition
    or value to what it denotes; ``condition_kinds`` maps every condition expression (of
    ``if``, and of the triggers of ``await``/``every``/``abort``/``suspend``/``loop each``)
    to :class:`ConditionKind`.
    """

    program: ast.Program
    interfaces: Mapping[str, MissionInterface]
    name_kinds: Mapping[ast.Name, NameKind] = field(default_factory=dict)
    condition_kinds: Mapping[ast.Expr, ConditionKind] = field(default_factory=dict)
    warnings: tuple = ()

    def interface(self, mission: str) -> MissionInterface:
        """The interface of ``mission`` (``KeyError`` if there is no such mission)."""
        return self.interfaces[mission]

    def kind_of(self, name: ast.Name) -> NameKind:
        """Whether an identifier node is a signal or a variable."""
        return self.name_kinds[name]

    def condition_kind(self, expr: ast.Expr) -> ConditionKind:
        """Whether a condition tests presence (SIGNAL) or computes a value (DATA)."""
        return self.condition_kinds[expr]


def _file_scope(program: ast.Program, problems: Problems) -> Scope:
    scope = Scope()
    for decl in program.signals:
        check_type(decl.type, decl.loc, problems)
        if decl.name in scope.names:
            problems.error(f"duplicate declaration of signal '{decl.name}'", decl.loc,
                           previous=scope.names[decl.name].decl.loc)
        else:
            scope.names[decl.name] = Binding(NameKind.SIGNAL, decl)
    return scope


def _mission(mission: ast.Mission, file_scope: Scope, checker: MissionChecker,
             problems: Problems) -> MissionInterface:
    scope = file_scope.child()
    for decl in mission.signals:
        check_type(decl.type, decl.loc, problems)
        shared = file_scope.names.get(decl.name)
        if shared is not None:
            problems.error(f"duplicate declaration of signal '{decl.name}' (already declared "
                           "at file level)", decl.loc, previous=shared.decl.loc)
            continue
        checker.declare(scope, decl.name, Binding(NameKind.SIGNAL, decl), decl.loc)
    checker.block(mission.body, scope)
    if mission.on_fatal is not None:
        checker.block(mission.on_fatal, scope)
    visible = sorted((b.decl for b in scope.visible().values()),
                     key=lambda d: (d.loc.line, d.loc.col))
    return MissionInterface(
        name=mission.name,
        inputs=tuple(d for d in visible if d.direction is ast.Direction.INPUT),
        outputs=tuple(d for d in visible if d.direction is ast.Direction.OUTPUT))


def _formulas(program: ast.Program, interfaces: dict[str, MissionInterface],
              tasks: dict[str, ast.RobotTask] | None, problems: Problems) -> None:
    exceptions = {"Timeout"}
    for task in (tasks or {}).values():
        exceptions.update(e.name for e in task.exceptions)
        exceptions.update(task.raisable())
    seen: dict[tuple, ast.Property | ast.Assumption] = {}
    for item in program.properties + program.assumptions:
        kind = "property" if isinstance(item, ast.Property) else "assumption"
        key = (kind, item.mission, item.name)
        if key in seen:
            problems.error(f"duplicate {kind} '{item.name}'", item.loc,
                           previous=seen[key].loc)
        seen.setdefault(key, item)
        if item.mission is not None and item.mission not in interfaces:
            problems.error(f"{kind} '{item.name}' names unknown mission '{item.mission}'",
                           item.loc)
            continue
        targets = [interfaces[item.mission]] if item.mission else list(interfaces.values())
        signals = set.intersection(*[{s.name for s in i.inputs + i.outputs}
                                     for i in targets]) if targets else set()
        check_formula(item.formula, f"{kind} '{item.name}'", signals, tasks, exceptions,
                      problems, {robot.name for robot in program.robots})
        if kind == "assumption" and ast.is_signal_formula(item.formula):
            problems.error(f"assumption '{item.name}' is a signal formula: assumptions "
                           "constrain the model checker's runs and must be plain LTL "
                           "(no signal comparison, no time bounds)", item.loc)


def _run(program: ast.Program, tasks: Iterable[ast.RobotTask]) -> tuple[Problems,
                                                                       CheckResult]:
    problems = Problems()
    robots = check_unique(program.robots, "robot", problems)
    known = check_unique(tuple(tasks) + program.robottasks, "robottask", problems)
    for task in program.robottasks:
        check_robottask(task, robots, problems)
    check_unique(program.missions, "mission", problems)
    file_scope = _file_scope(program, problems)
    checker = MissionChecker(problems, known or None)
    interfaces: dict[str, MissionInterface] = {}
    for mission in program.missions:
        interfaces.setdefault(mission.name, _mission(mission, file_scope, checker, problems))
    _formulas(program, interfaces, known or None, problems)
    return problems, CheckResult(program=program, interfaces=interfaces,
                                 name_kinds=dict(checker.name_kinds),
                                 condition_kinds=dict(checker.condition_kinds),
                                 warnings=tuple(problems.warnings))


def check(program: ast.Program, tasks: Iterable[ast.RobotTask] = ()) -> CheckResult:
    """Check the names of ``program``; raise :class:`OrccadError` on any error.

    ``tasks`` adds Robot-Tasks defined elsewhere (a library) to the file's own. The error
    raised is the first found; the others are attached as notes.
    """
    problems, result = _run(program, tasks)
    problems.raise_if_any()
    return result


def diagnose(program: ast.Program, tasks: Iterable[ast.RobotTask] = ()) -> list[OrccadError]:
    """Every error :func:`check` would report, in order, without raising."""
    return list(_run(program, tasks)[0].errors)
