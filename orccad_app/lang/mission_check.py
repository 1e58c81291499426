"""Name checking of one mission's statements.

Resolves every identifier against the scopes of :mod:`.scope`, classifies every condition,
and reports (into a :class:`~.scope.Problems`) undeclared signals and variables, emitting an
input, value/no-value mismatches on ``emit``, ``exit`` outside its trap, unknown
Robot-Tasks and parameters in ``run``, and ``catch`` of an exception nothing can raise.
"""

from __future__ import annotations

from dataclasses import dataclass

from orccad_app.diagnostics import OrccadError, SourceLocation
from orccad_app.lang import ast
from orccad_app.lang.walk import nodes, runs
from orccad_app.lang.declarations import check_type
from orccad_app.lang.run_args import argument_problem, runtime_reads
from orccad_app.lang.scope import (Binding, ConditionKind, NameKind, Problems, Scope,
                                   classify_condition, signal_leaves)

__all__ = ["MissionChecker", "UNIT_LOOKALIKES"]

#: Names that are probably a misspelt duration unit after ``await 2 ...``.
UNIT_LOOKALIKES = frozenset({
    "sec", "secs", "second", "seconds", "min", "mins", "minute", "minutes", "h", "hr", "hrs",
    "hour", "hours", "msec", "msecs", "millis", "usec", "usecs", "micros", "nsec", "nsecs",
    "nanos", "S", "MS", "US", "NS", "Ms", "Us", "Ns", "ps", "µs"})


@dataclass(frozen=True)
class _VarUse:
    """One access to a variable: its declaration, whether it assigns it, where."""

    decl: object
    write: bool
    loc: SourceLocation


class MissionChecker:
    """Checks the statements of one mission; results accumulate in the attributes.

    ``name_kinds`` maps every resolved :class:`~.ast.Name` to its kind and
    ``condition_kinds`` every condition expression to its :class:`ConditionKind`.
    ``tasks`` is ``None`` when Robot-Tasks are unknown (then ``run`` is not checked).
    """

    def __init__(self, problems: Problems, tasks: dict[str, ast.RobotTask] | None):
        self.problems = problems
        self.tasks = tasks
        self.name_kinds: dict[ast.Name, NameKind] = {}
        self.condition_kinds: dict[ast.Expr, ConditionKind] = {}
        self.traps: list[str] = []
        self._var_uses: list[_VarUse] = []  # every variable access, in traversal order

    def error(self, message: str, location: SourceLocation, **kwargs) -> None:
        self.problems.error(message, location, **kwargs)

    # ------------------------------------------------------------------ declarations

    def declare(self, scope: Scope, name: str, binding: Binding, loc: SourceLocation) -> None:
        """Add ``name`` to ``scope``: a duplicate in the same scope, or a name of another
        kind visible from an outer one, is an error."""
        if name in scope.names:
            self.error(f"duplicate declaration of '{name}'", loc,
                       previous=scope.names[name].decl.loc)
            return
        outer = scope.lookup(name)
        if outer is not None and outer.kind is not binding.kind:
            self.error(f"'{name}' is already declared as a {outer.kind.value}", loc,
                       previous=outer.decl.loc)
            return
        scope.names[name] = binding

    # ------------------------------------------------------------------ expressions

    def data(self, expr: ast.Expr | None, scope: Scope) -> None:
        """Check an expression used as a value."""
        if expr is None:
            return
        if isinstance(expr, ast.Name):
            self._value_name(expr, scope)
        elif isinstance(expr, (ast.LastValue, ast.PreValue)):
            self._last_value(expr, scope)
        elif isinstance(expr, ast.Call):
            self.error(f"unknown function '{expr.func}' (missions have no functions)",
                       expr.loc)
        elif isinstance(expr, ast.ParamRef):
            self.error(f"'{expr.module}.{expr.param}' is a Module-Task parameter: only the "
                       "value of a type-1 exception ('adjust') reads one", expr.loc)
        elif isinstance(expr, ast.Unary):
            self.data(expr.operand, scope)
        elif isinstance(expr, ast.Binary):
            self.data(expr.left, scope)
            self.data(expr.right, scope)
        elif isinstance(expr, ast.Vector):
            for item in expr.items:
                self.data(item, scope)

    def _value_name(self, name: ast.Name, scope: Scope) -> None:
        binding = scope.lookup(name.name)
        if binding is None:
            self.error(f"undeclared variable '{name.name}'", name.loc)
        elif binding.kind is NameKind.SIGNAL:
            self.name_kinds[name] = NameKind.SIGNAL
            self.error(f"signal '{name.name}' used as a value; write ?{name.name} for its "
                       "last value", name.loc)
        else:
            self.name_kinds[name] = NameKind.VARIABLE
            self._var_uses.append(_VarUse(binding.decl, False, name.loc))

    def _last_value(self, expr: ast.LastValue, scope: Scope) -> None:
        binding = scope.lookup(expr.signal)
        if binding is None:
            self.error(f"undeclared signal '{expr.signal}'", expr.loc)
        elif binding.kind is not NameKind.SIGNAL:
            self.error(f"'?{expr.signal}': '{expr.signal}' is a variable, not a signal",
                       expr.loc)
        elif not binding.valued:
            self.error(f"signal '{expr.signal}' carries no value; ?{expr.signal} needs a "
                       "valued signal", expr.loc)

    def condition(self, expr: ast.Expr, scope: Scope, counted: bool = False) -> None:
        """Check a condition, record its kind and the kind of each of its names."""
        leaves = signal_leaves(expr) or ()
        for leaf in leaves:
            if isinstance(leaf, ast.Name) and scope.lookup(leaf.name) is None:
                self._undeclared_signal(leaf, counted)
                return
        try:
            kind = classify_condition(expr, scope)
        except OrccadError as problem:
            self.error(problem.message, problem.location)
            return
        self.condition_kinds[expr] = kind
        if kind is ConditionKind.SIGNAL:
            for leaf in leaves:
                if isinstance(leaf, ast.Name):
                    self.name_kinds[leaf] = NameKind.SIGNAL
        else:
            if counted:
                self.error("a counted trigger needs a signal ('await 3 S')", expr.loc)
            self.data(expr, scope)

    def _undeclared_signal(self, name: ast.Name, counted: bool) -> None:
        if counted and name.name in UNIT_LOOKALIKES:
            self.error(f"bad duration unit '{name.name}' (expected one of s, ms, us, ns)",
                       name.loc)
        else:
            self.error(f"undeclared signal '{name.name}'", name.loc)

    def trigger(self, trigger: ast.Trigger, scope: Scope) -> None:
        if trigger.duration_ns is not None and trigger.immediate:
            self.error("'immediate' does not apply to a duration", trigger.loc)
        if trigger.count is not None:
            count = trigger.count
            if isinstance(count, ast.Number) and (not isinstance(count.value, int)
                                                  or count.value < 1):
                self.error(f"count must be a positive integer, not {count.text}", count.loc)
        if trigger.condition is not None:
            if isinstance(trigger.condition, ast.DurationLit) or any(
                    isinstance(leaf, ast.DurationLit)
                    for leaf in signal_leaves(trigger.condition) or ()):
                self.error("a duration cannot be combined with a condition",
                           trigger.condition.loc)
                return
            self.condition(trigger.condition, scope, counted=trigger.count is not None)

    # ------------------------------------------------------------------ statements

    def block(self, block: ast.Block, scope: Scope) -> None:
        """A block opens a scope; ``var`` declarations last to its end."""
        inner = scope.child()
        for stmt in block.statements:
            self.statement(stmt, inner)

    def statement(self, stmt: ast.Stmt, scope: Scope) -> None:
        handler = getattr(self, "_" + type(stmt).__name__.lower(), None)
        if handler is not None:
            handler(stmt, scope)

    def _blocks(self, scope: Scope, *blocks: ast.Block | None) -> None:
        for block in blocks:
            if block is not None:
                self.block(block, scope)

    def _emit(self, stmt: ast.Emit | ast.Sustain, scope: Scope) -> None:
        verb = "emit" if isinstance(stmt, ast.Emit) else "sustain"
        binding = scope.lookup(stmt.signal)
        self.data(stmt.value, scope)
        if binding is None:
            self.error(f"undeclared signal '{stmt.signal}'", stmt.signal_loc)
        elif binding.kind is not NameKind.SIGNAL:
            self.error(f"cannot {verb} '{stmt.signal}': it is a variable", stmt.signal_loc)
        elif binding.decl.direction is ast.Direction.INPUT:
            self.error(f"cannot {verb} input signal '{stmt.signal}'", stmt.signal_loc,
                       previous=binding.decl.loc, what="declared as input")
        elif binding.valued and stmt.value is None:
            self.error(f"signal '{stmt.signal}' carries a value of type {binding.decl.type}: "
                       f"write {verb} {stmt.signal}(value)", stmt.signal_loc)
        elif not binding.valued and stmt.value is not None:
            self.error(f"signal '{stmt.signal}' is pure (no value): write {verb} "
                       f"{stmt.signal}", stmt.value.loc)

    _sustain = _emit

    def _await(self, stmt: ast.Await, scope: Scope) -> None:
        self.trigger(stmt.trigger, scope)

    def _run(self, stmt: ast.Run, scope: Scope) -> None:
        for arg in stmt.args:
            self.data(arg.value, scope)
        if self.tasks is None:
            return
        task = self.tasks.get(stmt.task)
        if task is None:
            self.error(f"unknown Robot-Task '{stmt.task}'", stmt.task_loc)
            return
        self._run_args(stmt, task, scope)

    def _run_args(self, stmt: ast.Run, task: ast.RobotTask, scope: Scope) -> None:
        given: dict[str, ast.Arg] = {}
        for index, arg in enumerate(stmt.args):
            if arg.name is None:
                if index >= len(task.params):
                    self.error(f"too many arguments for Robot-Task '{task.name}'", arg.loc)
                    continue
                name = task.params[index].name
            elif task.param(arg.name) is None:
                self.error(f"Robot-Task '{task.name}' has no parameter '{arg.name}'", arg.loc)
                continue
            else:
                name = arg.name
            if name in given:
                self.error(f"parameter '{name}' given twice", arg.loc)
            given[name] = arg
            self._runtime_arg(task, name, arg, scope)
        for param in task.params:
            if param.default is None and param.name not in given:
                self.error(f"missing argument '{param.name}' of Robot-Task '{task.name}'",
                           stmt.task_loc)

    def _runtime_arg(self, task: ast.RobotTask, name: str, arg: ast.Arg, scope: Scope) -> None:
        """A run-time argument: typed against the parameter as far as the compiler sees."""
        param = task.param(name)
        reads = runtime_reads(arg.value)
        if param is None or not reads or any(
                scope.lookup(r.name if isinstance(r, ast.Name) else r.signal) is None
                for r in reads):
            return  # a constant (checked with the control scheme), or an undeclared name

        def lookup(signal_or_var: str):
            binding = scope.lookup(signal_or_var)
            return None if binding is None else binding.decl

        problem = argument_problem(param, arg.value, lookup)
        if problem is not None:
            self.error(f"Robot-Task '{task.name}': {problem}", arg.loc, previous=param.loc,
                       what="parameter declared")

    def _if(self, stmt: ast.If, scope: Scope) -> None:
        self.condition(stmt.condition, scope)
        self._blocks(scope, stmt.then, stmt.orelse)

    def _loop(self, stmt: ast.Loop, scope: Scope) -> None:
        self.block(stmt.body, scope)
        if stmt.each is not None:
            self.trigger(stmt.each, scope)

    def _repeat(self, stmt: ast.Repeat, scope: Scope) -> None:
        self.data(stmt.count, scope)
        count = stmt.count
        if isinstance(count, ast.Number) and (not isinstance(count.value, int)
                                              or count.value < 0):
            self.error(f"repeat count must be a non-negative integer, not {count.text}",
                       count.loc)
        self.block(stmt.body, scope)

    def _every(self, stmt: ast.Every, scope: Scope) -> None:
        self.trigger(stmt.trigger, scope)
        self.block(stmt.body, scope)

    def _abort(self, stmt: ast.Abort, scope: Scope) -> None:
        self.block(stmt.body, scope)
        self.trigger(stmt.trigger, scope)
        self._blocks(scope, stmt.handler)

    def _suspend(self, stmt: ast.Suspend, scope: Scope) -> None:
        self.block(stmt.body, scope)
        self.trigger(stmt.trigger, scope)

    def _trap(self, stmt: ast.Trap, scope: Scope) -> None:
        self.traps.append(stmt.name)
        try:
            self.block(stmt.body, scope)
        finally:
            self.traps.pop()
        self._blocks(scope, stmt.handler)

    def _exit(self, stmt: ast.Exit, scope: Scope) -> None:
        if stmt.name not in self.traps:
            self.error(f"'exit {stmt.name}' is not inside a trap named '{stmt.name}'",
                       stmt.loc)

    def _try(self, stmt: ast.Try, scope: Scope) -> None:
        self.block(stmt.body, scope)
        raisable = self._raisable(stmt.body)
        seen: dict[str, SourceLocation] = {}
        for catch in stmt.catches:
            for name in catch.exceptions:
                if name in seen:
                    self.error(f"exception '{name}' caught twice", catch.loc,
                               previous=seen[name], what="first caught")
                seen.setdefault(name, catch.loc)
                if raisable is not None and name not in raisable:
                    self.problems.warning(f"no Robot-Task run in this try can raise '{name}': "
                                          "this catch never runs", catch.loc)
            self.block(catch.body, scope)

    def _raisable(self, body: ast.Block) -> set[str] | None:
        """Exceptions the ``run`` statements of ``body`` can raise (``None``: unknown)."""
        if self.tasks is None:
            return None
        names: set[str] = {n.exception for n in nodes(body) if isinstance(n, ast.Fail)}
        if any(isinstance(n, ast.RunMission) for n in nodes(body)):
            return None  # a sub-mission may raise anything its Robot-Tasks raise
        for run in runs(body):
            task = self.tasks.get(run.task)
            if task is None:
                return None
            names.update(task.raisable())
            if run.within_ns is not None:
                names.add("Timeout")
        return names

    def _par(self, stmt: ast.Par | ast.Race, scope: Scope) -> None:
        per_branch = []
        for branch in stmt.branches:
            start = len(self._var_uses)
            self.block(branch, scope)
            per_branch.append(self._var_uses[start:])
        self._shared_variables(per_branch)

    def _shared_variables(self, per_branch: list[list[_VarUse]]) -> None:
        """Esterel v5's rule: a variable written in one parallel branch is neither read nor
        written in another (the branches are unordered; a signal carries values across)."""
        reported: set[int] = set()
        for index, uses in enumerate(per_branch):
            for write in (u for u in uses if u.write and id(u.decl) not in reported):
                other = next((u for j, others in enumerate(per_branch) if j != index
                              for u in others if u.decl is write.decl), None)
                if other is None:
                    continue
                reported.add(id(write.decl))
                self.error(f"variable '{write.decl.name}' is shared by parallel branches: "
                           f"assigned here and {'assigned' if other.write else 'read'} in "
                           "another branch (parallel branches are unordered; pass the value "
                           "through a signal, as in Esterel)", write.loc, previous=other.loc,
                           what="used in the other branch")

    _race = _par

    def _block(self, stmt: ast.Block, scope: Scope) -> None:
        self.block(stmt, scope)

    def _localsignals(self, stmt: ast.LocalSignals, scope: Scope) -> None:
        inner = scope.child()
        for decl in stmt.signals:
            check_type(decl.type, decl.loc, self.problems)
            self.declare(inner, decl.name, Binding(NameKind.SIGNAL, decl), decl.loc)
        self.block(stmt.body, inner)

    def _vardecl(self, stmt: ast.VarDecl, scope: Scope) -> None:
        self.data(stmt.value, scope)
        check_type(stmt.type, stmt.loc, self.problems)
        self.declare(scope, stmt.name, Binding(NameKind.VARIABLE, stmt), stmt.loc)

    def _assign(self, stmt: ast.Assign, scope: Scope) -> None:
        self.data(stmt.value, scope)
        binding = scope.lookup(stmt.name)
        if binding is None:
            self.error(f"undeclared variable '{stmt.name}'", stmt.loc)
        elif binding.kind is NameKind.SIGNAL:
            self.error(f"cannot assign to signal '{stmt.name}'; use emit", stmt.loc)
        else:
            self._var_uses.append(_VarUse(binding.decl, True, stmt.loc))
