"""File-level checks: duplicate declarations, types, Robot-Tasks and properties.

Each function reports into a :class:`~.scope.Problems`; :func:`orccad_app.lang.names.check`
calls them in order.
"""

from __future__ import annotations

import difflib
from typing import Iterable

from orccad_app.diagnostics import SourceLocation
from orccad_app.lang import ast
from orccad_app.lang.scope import Problems

__all__ = ["check_type", "check_unique", "check_robottask", "check_formula"]


def check_type(type_: str | None, loc: SourceLocation, problems: Problems) -> None:
    """A declared type must be one of :data:`~.ast.VALUE_TYPES`."""
    if type_ is None or type_ in ast.VALUE_TYPES:
        return
    close = difflib.get_close_matches(type_, sorted(ast.VALUE_TYPES), n=1)
    hint = f"; did you mean '{close[0]}'?" if close else \
        f" (one of {', '.join(sorted(ast.VALUE_TYPES))})"
    problems.error(f"unknown type '{type_}'{hint}", loc)


def check_unique(items: Iterable, what: str, problems: Problems) -> dict:
    """``{name: item}`` of ``items``; a second item of the same name is an error."""
    seen: dict = {}
    for item in items:
        if item.name in seen:
            problems.error(f"duplicate {what} '{item.name}'", item.loc,
                           previous=seen[item.name].loc)
        else:
            seen[item.name] = item
    return seen


def _leaves(expr, kind: type) -> Iterable:
    """Every node of type ``kind`` in ``expr`` (not below one, nor inside port references)."""
    if isinstance(expr, kind):
        yield expr
        return
    if isinstance(expr, ast.Arg):
        yield from _leaves(expr.value, kind)
        return
    for field in getattr(expr, "__dataclass_fields__", ()):
        value = getattr(expr, field)
        for item in value if isinstance(value, tuple) else (value,):
            if hasattr(item, "__dataclass_fields__") and not isinstance(
                    item, ast.PortRef | SourceLocation):
                yield from _leaves(item, kind)


def _names(expr) -> Iterable[ast.Name]:
    return _leaves(expr, ast.Name)


def _param_refs(expr) -> Iterable[ast.ParamRef]:
    """Every ``module.param`` read in ``expr``."""
    return _leaves(expr, ast.ParamRef)


def _task_expressions(task: ast.RobotTask):
    """Every expression of a Robot-Task body (not its parameter defaults)."""
    for call in (task.task_function, task.law):
        if call is not None:
            yield call
    for module in task.modules:
        yield from module.args
    for item in task.preconditions + task.postconditions:
        if hasattr(item, "observer"):
            yield item.observer
    for exc in task.exceptions:
        yield exc.source
        if exc.adjust is not None:
            yield exc.adjust.value


def check_robottask(task: ast.RobotTask, robots: dict[str, ast.Robot],
                    problems: Problems) -> None:
    """Parameters, robot, modules, connections, exceptions and names of one Robot-Task."""
    if task.robot not in robots:
        problems.error(f"unknown robot '{task.robot}' (declare it with "
                       f"'robot {task.robot} : TYPE;')", task.loc)
    params = check_unique(task.params, "parameter", problems)
    for param in task.params:
        check_type(param.type, param.loc, problems)
        for name in _names(param.default):
            problems.error(f"unknown name '{name.name}' in the default of '{param.name}'",
                           name.loc)
    modules = check_unique(task.modules, "module", problems)
    check_unique(task.exceptions, "exception", problems)
    for connect in task.connections:
        for end in (connect.source, connect.target):
            if end.component not in modules and end.component != task.robot:
                problems.error(f"unknown module '{end.component}' in robottask "
                               f"'{task.name}'", end.loc)
    for exc in task.exceptions:
        if exc.adjust is not None and exc.adjust.target.component not in modules:
            problems.error(f"unknown module '{exc.adjust.target.component}' in robottask "
                           f"'{task.name}'", exc.adjust.target.loc)
    adjusts = {id(exc.adjust.value) for exc in task.exceptions if exc.adjust is not None}
    for expr in _task_expressions(task):
        for ref in _param_refs(expr):
            if id(expr) not in adjusts:
                problems.error(f"'{ref.module}.{ref.param}' is a Module-Task parameter: only "
                               f"the value of a type-1 exception ('adjust') reads one", ref.loc)
            elif ref.module not in modules:
                problems.error(f"unknown module '{ref.module}' in robottask '{task.name}'",
                               ref.loc)
        for name in _names(expr):
            if name.name not in params:
                problems.error(f"unknown name '{name.name}' in robottask '{task.name}'",
                               name.loc)


def check_formula(formula: ast.Formula, where: str, signals: set[str],
                  tasks: dict[str, ast.RobotTask] | None, exceptions: set[str],
                  problems: Problems, robots: set[str] | None = None) -> None:
    """Atoms of a property or assumption: signals of the mission, known RTs/exceptions,
    declared robots and known functions in signal atoms (their ports are typed against the
    robot types by :mod:`orccad_app.lang.signal_types`)."""
    if isinstance(formula, ast.FCompare):
        for expr in (formula.left, formula.right):
            _check_signal_expr(expr, where, robots, problems)
    elif isinstance(formula, ast.FSignal):
        if formula.name not in signals:
            problems.error(f"unknown signal '{formula.name}' in {where}", formula.loc)
    elif isinstance(formula, ast.FPredicate):
        arg = formula.argument
        if formula.predicate == "raised":
            if tasks is not None and arg not in exceptions:
                problems.error(f"no Robot-Task can raise '{arg}'", formula.loc)
        elif tasks is not None and arg not in tasks:
            problems.error(f"unknown Robot-Task '{arg}' in {where}", formula.loc)
    elif isinstance(formula, ast.FUnary):
        check_formula(formula.operand, where, signals, tasks, exceptions, problems, robots)
    elif isinstance(formula, ast.FBinary):
        for side in (formula.left, formula.right):
            check_formula(side, where, signals, tasks, exceptions, problems, robots)


def _check_signal_expr(expr: ast.SignalExpr, where: str, robots: set[str] | None,
                       problems: Problems) -> None:
    if isinstance(expr, ast.SPort):
        if robots is not None and expr.robot not in robots:
            known = ", ".join(sorted(robots)) or "none declared"
            problems.error(f"unknown robot '{expr.robot}' in {where} (robots: {known})",
                           expr.loc)
    elif isinstance(expr, ast.SCall):
        arity = ast.SIGNAL_FUNCTIONS.get(expr.func)
        if arity is None:
            problems.error(f"unknown function '{expr.func}' in {where} (functions: "
                           f"{', '.join(ast.SIGNAL_FUNCTIONS)})", expr.loc)
        elif len(expr.args) != arity[0]:
            problems.error(f"{expr.func}() takes {arity[0]} argument, got {len(expr.args)}",
                           expr.loc)
        for arg in expr.args:
            _check_signal_expr(arg, where, robots, problems)
    elif isinstance(expr, ast.SNeg):
        _check_signal_expr(expr.operand, where, robots, problems)
    elif isinstance(expr, ast.SArith):
        for side in (expr.left, expr.right):
            _check_signal_expr(side, where, robots, problems)
