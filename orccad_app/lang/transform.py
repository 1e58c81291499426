"""Turn the lark parse tree of ``plan.lark`` into the dataclass AST of :mod:`.ast`.

One method per grammar alias: here the program, its declarations, statements and missions; the
expressions' rules in :mod:`.transform_expr`, the temporal logic's in :mod:`.transform_formula`
and the Robot-Tasks' in :mod:`.transform_rt` (mixins of :class:`ToAst`). Only
:func:`orccad_app.lang.parser.parse` uses this module; nothing downstream ever sees a lark tree.
"""

from __future__ import annotations

from lark import Token, Transformer

from orccad_app.diagnostics import OrccadError, SourceLocation
from orccad_app.lang import ast
from orccad_app.lang.transform_expr import ExpressionRules, unescape as _unescape
from orccad_app.lang.transform_formula import FormulaRules
from orccad_app.lang.transform_rt import RobotTaskRules, duration_to_ns, rule as _rule

__all__ = ["ToAst"]


def _simple(cls):
    @_rule
    def method(self, meta):
        return cls(loc=self.loc(meta))
    return method


def _opt(token: Token | None) -> str | None:
    return None if token is None else str(token)


class ToAst(RobotTaskRules, ExpressionRules, FormulaRules, Transformer):
    """The transformer; ``filename`` goes into every :class:`SourceLocation`."""

    def __init__(self, filename: str):
        super().__init__(visit_tokens=False)
        self.filename = filename

    # ------------------------------------------------------------------ locations

    def loc(self, meta) -> SourceLocation:
        """Location of a rule's span."""
        if getattr(meta, "empty", True):
            return SourceLocation(self.filename, 0, 0)
        return SourceLocation(self.filename, meta.line, meta.column,
                              meta.end_line, meta.end_column)

    def tloc(self, token: Token) -> SourceLocation:
        """Location of one token."""
        return SourceLocation(self.filename, token.line, token.column,
                              token.end_line, token.end_column)

    def ns(self, token: Token) -> int:
        return duration_to_ns(str(token), self.tloc(token))

    # ------------------------------------------------------------------ root, declarations

    @_rule
    def start(self, meta, *items):
        flat = []
        for item in items:
            flat.extend(item if isinstance(item, list) else [item])
        return ast.Program(filename=self.filename, items=tuple(flat), loc=self.loc(meta))

    @_rule
    def import_decl(self, meta, path, *names):
        return ast.Import(path=_unescape(str(path)),
                          names=tuple(ast.ImportedName(name=str(n), loc=self.tloc(n))
                                      for n in names),
                          path_loc=self.tloc(path), loc=self.loc(meta))

    @_rule
    def robot_decl(self, meta, name, type_, args):
        return ast.Robot(name=str(name), type=str(type_), args=args or (), loc=self.loc(meta))

    @_rule
    def type_name(self, meta, *token):
        return str(token[0]) if token else "duration"

    @_rule
    def sig_item(self, meta, name, type_, init, combine):
        return (name, _opt(type_), init, combine)

    def _signals(self, direction: ast.Direction, items) -> list[ast.SignalDecl]:
        return [ast.SignalDecl(name=str(name), direction=direction, type=type_, init=init,
                               combine=combine, loc=self.tloc(name))
                for name, type_, init, combine in items]

    @_rule
    def combine_add(self, meta):
        return "+"

    @_rule
    def combine_mul(self, meta):
        return "*"

    @_rule
    def combine_and(self, meta):
        return "and"

    @_rule
    def combine_or(self, meta):
        return "or"

    @_rule
    def combine_name(self, meta, token):
        if str(token) not in ("min", "max"):
            raise OrccadError(f"unknown combine operator '{token}' (expected + * min max and "
                              "or)", self.tloc(token))
        return str(token)

    @_rule
    def relation_exclusive(self, meta, *names):
        return ast.Relation(kind="#", signals=tuple(str(n) for n in names), loc=self.loc(meta))

    @_rule
    def relation_implies(self, meta, left, right):
        return ast.Relation(kind="=>", signals=(str(left), str(right)), loc=self.loc(meta))

    @_rule
    def signature(self, meta, *parts):
        flat = []
        for part in parts:
            if part is not None:
                flat.extend(part)
        return ("signature", tuple(flat))

    @_rule
    def input_decl(self, meta, *items):
        return self._signals(ast.Direction.INPUT, items)

    @_rule
    def output_decl(self, meta, *items):
        return self._signals(ast.Direction.OUTPUT, items)

    # ------------------------------------------------------------------ statements

    nothing, pause, halt = _simple(ast.Nothing), _simple(ast.Pause), _simple(ast.Halt)

    @_rule
    def block(self, meta, *statements):
        return ast.Block(statements=tuple(statements), loc=self.loc(meta))

    @_rule
    def nested_block(self, meta, block):
        return block

    @_rule
    def statement(self, meta, stmt):
        return stmt

    @_rule
    def emit(self, meta, name, value):
        return ast.Emit(signal=str(name), value=value, signal_loc=self.tloc(name),
                        loc=self.loc(meta))

    @_rule
    def sustain(self, meta, name, value):
        return ast.Sustain(signal=str(name), value=value, signal_loc=self.tloc(name),
                           loc=self.loc(meta))

    @_rule
    def trigger_expr(self, meta, expr):
        if isinstance(expr, ast.DurationLit):
            return ast.Trigger(duration_ns=expr.duration_ns, loc=self.loc(meta))
        return ast.Trigger(condition=expr, loc=self.loc(meta))

    @_rule
    def trigger_immediate(self, meta, _immediate, expr):
        if isinstance(expr, ast.DurationLit):
            return ast.Trigger(duration_ns=expr.duration_ns, immediate=True, loc=self.loc(meta))
        return ast.Trigger(condition=expr, immediate=True, loc=self.loc(meta))

    @_rule
    def trigger_count(self, meta, count, expr):
        return ast.Trigger(condition=expr, count=self.number(None, count), loc=self.loc(meta))

    @_rule
    def await_(self, meta, trigger):
        return ast.Await(trigger=trigger, loc=self.loc(meta))

    @_rule
    def run(self, meta, name, args, within):
        return ast.Run(task=str(name), args=args or (),
                       within_ns=None if within is None else self.ns(within),
                       task_loc=self.tloc(name), loc=self.loc(meta))

    @_rule
    def run_mission(self, meta, name, renames):
        return ast.RunMission(mission=str(name), renames=renames or (),
                              mission_loc=self.tloc(name), loc=self.loc(meta))

    @_rule
    def renaming(self, meta, *renames):
        return tuple(r for r in renames if r is not None)

    @_rule
    def rename(self, meta, formal, actual):
        return ast.Rename(formal=str(formal), actual=str(actual), loc=self.loc(meta))

    @_rule
    def fail(self, meta, name):
        return ast.Fail(exception=str(name), loc=self.loc(meta))

    @_rule
    def if_(self, meta, condition, then, orelse):
        return ast.If(condition=condition, then=then, orelse=orelse, loc=self.loc(meta))

    @_rule
    def else_block(self, meta, block):
        return block

    @_rule
    def else_if(self, meta, if_stmt):
        return ast.Block(statements=(if_stmt,), loc=if_stmt.loc)

    @_rule
    def loop(self, meta, body):
        return ast.Loop(body=body, loc=self.loc(meta))

    @_rule
    def loop_each(self, meta, body, trigger):
        return ast.Loop(body=body, each=trigger, loc=self.loc(meta))

    @_rule
    def repeat(self, meta, count, body):
        return ast.Repeat(count=count, body=body, loc=self.loc(meta))

    @_rule
    def every(self, meta, trigger, body):
        return ast.Every(trigger=trigger, body=body, loc=self.loc(meta))

    @_rule
    def abort(self, meta, weak, body, trigger):
        return ast.Abort(body=body, trigger=trigger, weak=weak is not None, loc=self.loc(meta))

    @_rule
    def abort_do(self, meta, weak, body, trigger, handler):
        return ast.Abort(body=body, trigger=trigger, weak=weak is not None, handler=handler,
                         loc=self.loc(meta))

    @_rule
    def suspend(self, meta, body, trigger):
        return ast.Suspend(body=body, trigger=trigger, loc=self.loc(meta))

    @_rule
    def trap(self, meta, name, body, handler):
        return ast.Trap(name=str(name), body=body, handler=handler, loc=self.loc(meta))

    @_rule
    def exit(self, meta, name):
        return ast.Exit(name=str(name), loc=self.loc(meta))

    @_rule
    def catch(self, meta, *parts):
        *names, body = parts
        return ast.Catch(exceptions=tuple(str(n) for n in names), body=body, loc=self.loc(meta))

    @_rule
    def try_(self, meta, body, *catches):
        return ast.Try(body=body, catches=tuple(catches), loc=self.loc(meta))

    @_rule
    def par(self, meta, *branches):
        return ast.Par(branches=tuple(branches), loc=self.loc(meta))

    @_rule
    def race(self, meta, *branches):
        return ast.Race(branches=tuple(branches), loc=self.loc(meta))

    @_rule
    def local_signals(self, meta, *parts):
        *items, body = parts
        return ast.LocalSignals(signals=tuple(self._signals(ast.Direction.LOCAL, items)),
                                body=body, loc=self.loc(meta))

    @_rule
    def var_decl(self, meta, name, type_, value):
        return ast.VarDecl(name=str(name), value=value, type=_opt(type_), loc=self.loc(meta))

    @_rule
    def assign(self, meta, name, value):
        return ast.Assign(name=str(name), value=value, loc=self.loc(meta))

    # ------------------------------------------------------------------ missions

    @_rule
    def on_fatal(self, meta, block):
        return ("on_fatal", block)

    @_rule
    def mission(self, meta, name, signature, *items):
        *items, on_fatal = items
        own = () if signature is None else signature[1]
        signals, statements, relations = list(own), [], []
        for item in items:
            if isinstance(item, list):
                signals.extend(item)
            elif isinstance(item, ast.Relation):
                relations.append(item)
            else:
                statements.append(item)
        body_loc = statements[0].loc if statements else self.loc(meta)
        if statements:
            last = statements[-1].loc
            body_loc = SourceLocation(self.filename, body_loc.line, body_loc.col,
                                      last.end_line, last.end_col)
        return ast.Mission(name=str(name), signals=tuple(signals),
                           body=ast.Block(statements=tuple(statements), loc=body_loc),
                           on_fatal=None if on_fatal is None else on_fatal[1],
                           signature=tuple(own), relations=tuple(relations),
                           loc=self.loc(meta))
