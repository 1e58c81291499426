"""Lowering of a checked mission (plan-language AST) to the reactive kernel IR.

Names are resolved lexically: file-level signals, then the mission's, then ``signal`` blocks;
``var`` declarations are visible to the end of their block; ``exit T`` names the innermost
enclosing ``trap T``. A condition is a *presence test* when it is made of signal names under
``not``/``and``/``or``, and a *data test* when it names no signal (``?S`` reads a value and is
data); mixing both in one condition is an error that suggests nesting two ``if``.

Statements that involve Robot-Tasks (``run``, ``try``, ``on fatal``) belong to the
application level and are lowered by :mod:`orccad_app.robottask` when it is there; here they
are reported as not available. Signal declarations are lowered by :mod:`.declarations`;
the size of a mission once its sub-missions are inlined is budgeted by :mod:`.inlining`.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from orccad_app.diagnostics import OrccadError, SourceLocation
from orccad_app.lang import ast
from orccad_app.reactive import derived as d
from orccad_app.reactive import ir
from orccad_app.reactive.declarations import mission_interface, signal_decl
from orccad_app.reactive.inlining import MAX_INLINED_NODES, inlined_size
from orccad_app.reactive.labels import MissionLabel

__all__ = ["lower_mission", "Lowerer", "Scope", "not_yet"]


@dataclass
class Scope:
    """One lexical level: signals, variables and traps declared there."""

    parent: "Scope | None" = None
    signals: dict[str, ir.SignalDecl] = field(default_factory=dict)
    variables: dict[str, ir.VarDecl] = field(default_factory=dict)
    traps: dict[str, ir.TrapDecl] = field(default_factory=dict)

    def lookup(self, table: str, name: str):
        scope: Scope | None = self
        while scope is not None:
            found = getattr(scope, table).get(name)
            if found is not None:
                return found
            scope = scope.parent
        return None

    def child(self) -> "Scope":
        return Scope(parent=self)



def lower_mission(program: ast.Program, mission: ast.Mission,
                  lowerer: type["Lowerer"] | None = None) -> ir.Program:
    """The kernel program of ``mission``.

    The base :class:`Lowerer` handles the reactive statements; the application level passes
    its subclass, which adds ``run``, ``try`` and ``on fatal``.
    """
    return (lowerer or Lowerer)(program, mission).lower()


def not_yet(what: str, loc: SourceLocation):
    raise OrccadError(f"{what} needs Robot-Tasks, which the application level compiles; "
                      "use the application compiler for this mission", loc)


class Lowerer:
    """Statement-by-statement translation; one instance per mission."""

    def __init__(self, program: ast.Program, mission: ast.Mission):
        if inlined_size(program, mission) > MAX_INLINED_NODES:
            raise OrccadError(f"mission '{mission.name}' expands to more than "
                              f"{MAX_INLINED_NODES} syntax nodes once its sub-missions are "
                              "inlined (each 'run mission' copies the sub-mission, and "
                              "sub-missions that run each other several times multiply): "
                              "refused before building it", mission.loc)
        self.source = program
        self.mission = mission
        self.inputs, self.outputs = mission_interface(program, mission)
        self.scope = Scope()
        for decl in (*self.inputs, *self.outputs):
            self.scope.signals[decl.name] = decl
        self._inlining: tuple[str, ...] = (mission.name,)  # the sub-missions being inlined
        self._instances: dict[str, int] = {}  # sub-mission -> instances so far

    def lower(self) -> ir.Program:
        """The whole mission; subclasses wrap the body (statuses, ``on fatal``)."""
        if self.mission.on_fatal is not None:
            not_yet("'on fatal'", self.mission.on_fatal.loc)
        body = self.block(self.mission.body, self.scope)
        return ir.Program(self.mission.name, self.inputs, self.outputs, body, self.mission.loc,
                          relations=self.relations())

    def relations(self) -> tuple[ir.Relation, ...]:
        """The file's and the mission's relations, over the mission's inputs."""
        out = []
        file_level = self.source.relations
        for relation in (*file_level, *self.mission.relations):
            decls = []
            for name in relation.signals:
                decl = self.scope.signals.get(name)
                if decl is None:
                    if any(relation is r for r in file_level):
                        break  # a file-level relation over another mission's signals
                    raise OrccadError(f"relation: undeclared signal '{name}'", relation.loc)
                if decl.kind != ir.INPUT:
                    raise OrccadError(f"relation {name}: '{name}' is not an input signal "
                                      "(relations constrain the environment)", relation.loc)
                decls.append(decl)
            else:
                out.append(ir.Relation(relation.kind, tuple(decls), relation.loc))
        return tuple(out)

    # ------------------------------------------------------------------ statements
    def block(self, block: ast.Block, scope: Scope) -> ir.Stmt:
        inner = scope.child()
        return d.seq(*(self.stmt(s, inner) for s in block.statements), loc=block.loc)

    def stmt(self, s: ast.Stmt, scope: Scope) -> ir.Stmt:
        method = getattr(self, "_" + type(s).__name__.lower(), None)
        if method is None:
            not_yet(f"'{type(s).__name__.lower()}'", s.loc)
        return method(s, scope)

    def _block(self, s: ast.Block, scope: Scope) -> ir.Stmt:
        return self.block(s, scope)

    def _nothing(self, s: ast.Nothing, scope: Scope) -> ir.Stmt:
        return ir.Nothing(s.loc)

    def _pause(self, s: ast.Pause, scope: Scope) -> ir.Stmt:
        return ir.Pause(s.loc)

    def _halt(self, s: ast.Halt, scope: Scope) -> ir.Stmt:
        return d.halt(s.loc)

    def _emit(self, s: ast.Emit, scope: Scope) -> ir.Stmt:
        signal = self._emittable(s.signal, s.value, s.signal_loc or s.loc, scope)
        value = None if s.value is None else self.expr(s.value, scope)
        return ir.Emit(signal, value, s.loc)

    def _sustain(self, s: ast.Sustain, scope: Scope) -> ir.Stmt:
        signal = self._emittable(s.signal, s.value, s.signal_loc or s.loc, scope)
        value = None if s.value is None else self.expr(s.value, scope)
        return d.sustain(signal, value, s.loc)

    def _await(self, s: ast.Await, scope: Scope) -> ir.Stmt:
        trigger = s.trigger
        if trigger.duration_ns is not None:
            return d.await_duration(ir.Const(trigger.duration_ns, trigger.loc), s.loc)
        test = self.condition(trigger.condition, scope)
        if trigger.count is not None:
            if trigger.immediate:
                raise OrccadError("'await immediate' cannot be counted", s.loc)
            return d.await_count(self.expr(trigger.count, scope), test, s.loc)
        return d.await_signal(test, immediate=trigger.immediate, loc=s.loc)

    def _if(self, s: ast.If, scope: Scope) -> ir.Stmt:
        test = self.condition(s.condition, scope)
        orelse = ir.Nothing(s.loc) if s.orelse is None else self.block(s.orelse, scope)
        return ir.Present(test, self.block(s.then, scope), orelse, s.loc)

    def _loop(self, s: ast.Loop, scope: Scope) -> ir.Stmt:
        body = self.block(s.body, scope)
        if s.each is None:
            return ir.Loop(body, s.loc)
        if s.each.count is not None:
            run = self.counted_abort(d.seq(body, d.halt(s.loc)), s.each, scope, s.loc)
            return ir.Loop(run, s.loc, "loop … each")
        setup, test, rearm = self.trigger(s.each, scope, "loop … each")
        run = d.abort(d.seq(body, d.halt(s.loc)), test, loc=s.loc)
        return d.seq(*setup, ir.Loop(d.seq(run, *rearm), s.loc, "loop … each"))

    def _repeat(self, s: ast.Repeat, scope: Scope) -> ir.Stmt:
        return d.repeat(self.expr(s.count, scope), self.block(s.body, scope), s.loc)

    def _every(self, s: ast.Every, scope: Scope) -> ir.Stmt:
        body = self.block(s.body, scope)
        if s.trigger.duration_ns is not None:
            return d.every_duration(ir.Const(s.trigger.duration_ns, s.trigger.loc), body, s.loc)
        test = self.condition(s.trigger.condition, scope)
        if s.trigger.count is not None:
            # every n S { p } = await n S; loop { abort { p; halt } when n S }
            start = d.await_count(self.expr(s.trigger.count, scope), test, s.loc)
            run = self.counted_abort(d.seq(body, d.halt(s.loc)), s.trigger, scope, s.loc)
            return d.seq(start, ir.Loop(run, s.loc, "every"))
        return d.every_signal(test, body, immediate=s.trigger.immediate, loc=s.loc)

    def counted_abort(self, body: ir.Stmt, trigger: ast.Trigger, scope: Scope,
                      loc: SourceLocation, weak: bool = False,
                      handler: ir.Stmt | None = None) -> ir.Stmt:
        """``abort body when n S``: a watcher counts the occurrences (``await n S``) and emits
        a hidden local signal that preempts the body, as Esterel v5 expands it."""
        if trigger.immediate:
            raise OrccadError("a counted trigger cannot be 'immediate'", trigger.loc)
        test = self.condition(trigger.condition, scope)
        return d.abort_count(body, self.expr(trigger.count, scope), test, weak=weak,
                             handler=handler, loc=loc)

    def _abort(self, s: ast.Abort, scope: Scope) -> ir.Stmt:
        handler = None if s.handler is None else self.block(s.handler, scope)
        body = self.block(s.body, scope)
        if s.trigger.count is not None:
            return self.counted_abort(body, s.trigger, scope, s.loc, s.weak, handler)
        setup, test, _ = self.trigger(s.trigger, scope, "abort")
        return d.seq(*setup, d.abort(body, test, weak=s.weak, immediate=s.trigger.immediate,
                                     handler=handler, loc=s.loc))

    def _suspend(self, s: ast.Suspend, scope: Scope) -> ir.Stmt:
        if s.trigger.duration_ns is not None:
            raise OrccadError("'suspend' needs a signal condition, not a duration", s.trigger.loc)
        if s.trigger.count is not None:
            raise OrccadError("'suspend' cannot be counted: it freezes its body in each instant "
                              "where its condition holds (count with 'await n S' and a local "
                              "signal instead)", s.trigger.loc)
        test = self.condition(s.trigger.condition, scope)
        return d.suspend(self.block(s.body, scope), test, immediate=s.trigger.immediate, loc=s.loc)

    def _trap(self, s: ast.Trap, scope: Scope) -> ir.Stmt:
        inner = scope.child()
        trap = ir.TrapDecl(s.name, s.loc)
        inner.traps[s.name] = trap
        body = self.block(s.body, inner)
        handler = None if s.handler is None else self.block(s.handler, scope)
        return d.trap_handle(trap, body, handler, s.loc)

    def _exit(self, s: ast.Exit, scope: Scope) -> ir.Stmt:
        trap = scope.lookup("traps", s.name)
        if trap is None:
            raise OrccadError(f"'exit {s.name}' is not inside a trap named {s.name}", s.loc)
        return ir.Exit(trap, s.loc)

    def _par(self, s: ast.Par, scope: Scope) -> ir.Stmt:
        return ir.Par(tuple(self.block(b, scope) for b in s.branches), s.loc)

    def _race(self, s: ast.Race, scope: Scope) -> ir.Stmt:
        return d.race(tuple(self.block(b, scope) for b in s.branches), s.loc)

    def _localsignals(self, s: ast.LocalSignals, scope: Scope) -> ir.Stmt:
        inner = scope.child()
        decls = []
        for decl in s.signals:
            local = signal_decl(decl, ir.LOCAL)
            inner.signals[decl.name] = local
            decls.append(local)
        return ir.Local(tuple(decls), self.block(s.body, inner), s.loc)

    def _fail(self, s: ast.Fail, scope: Scope) -> ir.Stmt:
        not_yet("'fail'", s.loc)

    def _runmission(self, s: ast.RunMission, scope: Scope) -> ir.Stmt:
        """``run mission M [formal / actual, ...]``: M's body inlined, its signals bound."""
        target = self.source.mission(s.mission)
        if target is None:
            raise OrccadError(f"unknown mission '{s.mission}'", s.mission_loc or s.loc)
        stack = self._inlining
        if target.name in stack:
            chain = " -> ".join((*stack, target.name))
            raise OrccadError(f"recursive sub-mission: {chain}", s.loc)
        if target.on_fatal is not None:
            raise OrccadError(f"mission '{target.name}' has an 'on fatal' block: it cannot run "
                              "as a sub-mission", s.loc)
        inner = Scope()
        inner.signals.update({d.name: d for d in (*self.inputs, *self.outputs)
                              if any(d.name == f.name for f in self.source.signals)})
        inner.signals.update(self._bind(target, s, scope))
        self._instances[target.name] = self._instances.get(target.name, 0) + 1
        label = MissionLabel(target.name, self._instances[target.name], target.loc, s.loc)
        self._inlining = (*stack, target.name)
        try:
            body = self.block(target.body, inner)
        finally:
            self._inlining = stack
        return ir.Mark(label, body, s.loc)

    def _bind(self, target: ast.Mission, s: ast.RunMission, scope: Scope) -> dict:
        """The caller's signal for each of the sub-mission's (renamed, else same name)."""
        renames = {}
        for rename in s.renames:
            if rename.formal in renames:
                raise OrccadError(f"signal '{rename.formal}' renamed twice", rename.loc)
            if not any(f.name == rename.formal for f in target.signals):
                raise OrccadError(f"mission '{target.name}' has no signal '{rename.formal}' "
                                  f"(its signals: {', '.join(f.name for f in target.signals)})",
                                  rename.loc)
            renames[rename.formal] = rename
        bound = {}
        for formal in target.signals:
            rename = renames.get(formal.name)
            actual_name = rename.actual if rename else formal.name
            where = rename.loc if rename else s.loc
            actual = scope.lookup("signals", actual_name)
            if actual is None:
                raise OrccadError(f"sub-mission '{target.name}' needs signal '{formal.name}': "
                                  f"'{actual_name}' is not declared here (rename it: "
                                  f"[{formal.name} / …])", where)
            if actual.type != formal.type:
                raise OrccadError(
                    f"signature mismatch: '{formal.name}' of mission '{target.name}' is "
                    f"{formal.type or 'pure'}, '{actual_name}' is {actual.type or 'pure'}", where)
            if formal.direction is ast.Direction.OUTPUT and actual.kind == ir.INPUT:
                raise OrccadError(
                    f"signature mismatch: mission '{target.name}' emits '{formal.name}', but "
                    f"'{actual_name}' is an input here", where)
            bound[formal.name] = actual
        return bound

    def _vardecl(self, s: ast.VarDecl, scope: Scope) -> ir.Stmt:
        value = self.expr(s.value, scope)  # the initial value cannot see the new variable
        var = ir.VarDecl(s.name, s.loc)
        scope.variables[s.name] = var
        return ir.Assign(var, value, s.loc)

    def _assign(self, s: ast.Assign, scope: Scope) -> ir.Stmt:
        var = scope.lookup("variables", s.name)
        if var is None:
            raise OrccadError(f"undeclared variable '{s.name}' (declare it with 'var "
                              f"{s.name} := …;')", s.loc)
        return ir.Assign(var, self.expr(s.value, scope), s.loc)

    # ------------------------------------------------------------------ helpers
    def _emittable(self, name: str, value, loc: SourceLocation, scope: Scope) -> ir.SignalDecl:
        signal = self.signal(name, loc, scope)
        if signal.kind == ir.INPUT:
            raise OrccadError(f"'{name}' is an input signal: the mission cannot emit it", loc)
        if signal.valued and value is None:
            raise OrccadError(f"signal '{name}' carries a {signal.type}: emit it with a value, "
                              f"'emit {name}(…)'", loc)
        if not signal.valued and value is not None:
            raise OrccadError(f"signal '{name}' is pure: it cannot carry a value", loc)
        return signal

    def _no_count(self, trigger: ast.Trigger, what: str) -> None:
        if trigger.count is not None:
            raise OrccadError(f"a count is only allowed in 'await', not in '{what}'", trigger.loc)

    def signal(self, name: str, loc: SourceLocation, scope: Scope) -> ir.SignalDecl:
        signal = scope.lookup("signals", name)
        if signal is None:
            raise OrccadError(f"undeclared signal '{name}'", loc)
        return signal

    def trigger(self, trigger: ast.Trigger, scope: Scope, what: str):
        """(set-up statements, test, re-arm statements) of a preemption trigger."""
        if trigger.duration_ns is None:
            self._no_count(trigger, what)
            return (), self.condition(trigger.condition, scope), ()
        period = ir.Const(trigger.duration_ns, trigger.loc)
        timer, start, test = d.deadline(period, trigger.loc)
        rearm = ir.Assign(timer, ir.Binary("+", ir.VarRef(timer), period), trigger.loc)
        return (start,), test, (rearm,)

    # ------------------------------------------------------------------ conditions
    def _mentions_signal(self, e: ast.Expr, scope: Scope) -> bool:
        if isinstance(e, ast.PreSignal):
            return True
        if isinstance(e, ast.Name):
            return scope.lookup("variables", e.name) is None and \
                scope.lookup("signals", e.name) is not None
        if isinstance(e, ast.Unary):
            return self._mentions_signal(e.operand, scope)
        if isinstance(e, ast.Binary):
            return self._mentions_signal(e.left, scope) or self._mentions_signal(e.right, scope)
        return False

    def _presence_shaped(self, e: ast.Expr) -> bool:
        if isinstance(e, (ast.Name, ast.PreSignal)):
            return True
        if isinstance(e, ast.Unary) and e.op == "not":
            return self._presence_shaped(e.operand)
        if isinstance(e, ast.Binary) and e.op in ("and", "or"):
            return self._presence_shaped(e.left) and self._presence_shaped(e.right)
        return False

    def _mentions_variable(self, e: ast.Expr, scope: Scope) -> bool:
        if isinstance(e, ast.Name):
            return scope.lookup("variables", e.name) is not None
        if isinstance(e, ast.Unary):
            return self._mentions_variable(e.operand, scope)
        if isinstance(e, ast.Binary):
            return self._mentions_variable(e.left, scope) or self._mentions_variable(e.right, scope)
        return False

    def condition(self, e: ast.Expr, scope: Scope) -> ir.Test:
        if self._presence_shaped(e) and not self._mentions_variable(e, scope):
            return self._presence(e, scope)  # unknown names are reported as signals
        if not self._mentions_signal(e, scope):
            return ir.DataTest(self.expr(e, scope), e.loc)
        return self._presence(e, scope)

    def _presence(self, e: ast.Expr, scope: Scope) -> ir.Test:
        if isinstance(e, ast.PreSignal):
            return ir.PreRef(self.signal(e.signal, e.loc, scope), e.loc)
        if isinstance(e, ast.Name):
            if scope.lookup("variables", e.name) is not None:
                self._mixed(e)
            return ir.SigRef(self.signal(e.name, e.loc, scope), e.loc)
        if isinstance(e, ast.Unary) and e.op == "not":
            return ir.SigNot(self._presence(e.operand, scope), e.loc)
        if isinstance(e, ast.Binary) and e.op in ("and", "or"):
            left, right = self._presence(e.left, scope), self._presence(e.right, scope)
            return (ir.SigAnd if e.op == "and" else ir.SigOr)(left, right, e.loc)
        self._mixed(e)

    def _mixed(self, e: ast.Expr):
        raise OrccadError("this condition mixes signal presence and data values; test them "
                          "in two nested 'if' statements", e.loc)

    # ------------------------------------------------------------------ expressions
    def expr(self, e: ast.Expr, scope: Scope) -> ir.Expr:
        if isinstance(e, (ast.Number, ast.String, ast.Bool)):
            return ir.Const(e.value, e.loc)
        if isinstance(e, ast.DurationLit):
            return ir.Const(e.duration_ns, e.loc)
        if isinstance(e, ast.Name):
            var = scope.lookup("variables", e.name)
            if var is not None:
                return ir.VarRef(var, e.loc)
            if scope.lookup("signals", e.name) is not None:
                raise OrccadError(f"'{e.name}' is a signal: its presence is not a value here "
                                  f"(use ?{e.name} for its value)", e.loc)
            raise OrccadError(f"undeclared variable '{e.name}'", e.loc)
        if isinstance(e, ast.LastValue):
            signal = self.signal(e.signal, e.loc, scope)
            if not signal.valued:
                raise OrccadError(f"?{e.signal}: signal '{e.signal}' is pure and has no value",
                                  e.loc)
            return ir.SigValue(signal, e.loc)
        if isinstance(e, ast.PreValue):
            signal = self.signal(e.signal, e.loc, scope)
            if not signal.valued:
                raise OrccadError(f"pre(?{e.signal}): signal '{e.signal}' is pure and has no "
                                  "value", e.loc)
            return ir.PreValue(signal, e.loc)
        if isinstance(e, ast.PreSignal):
            raise OrccadError(f"pre({e.signal}) is a presence test, not a value", e.loc)
        if isinstance(e, ast.Vector):
            return ir.VectorExpr(tuple(self.expr(i, scope) for i in e.items), e.loc)
        if isinstance(e, ast.Unary):
            return ir.Unary(e.op, self.expr(e.operand, scope), e.loc)
        if isinstance(e, ast.Binary):
            return ir.Binary(e.op, self.expr(e.left, scope), self.expr(e.right, scope), e.loc)
        raise OrccadError(f"'{getattr(e, 'func', '?')}(…)' is not a value in a mission "
                          "expression", e.loc)
