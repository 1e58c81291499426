"""Turn the lark parse tree of ``plan.lark`` into the dataclass AST of :mod:`.ast`.

One method per grammar alias. Only :func:`orccad_app.lang.parser.parse` uses this module;
nothing downstream ever sees a lark tree.
"""

from __future__ import annotations

import math

from lark import Token, Transformer

from orccad_app.diagnostics import OrccadError, SourceLocation
from orccad_app.lang import ast
from orccad_app.lang.transform_rt import RobotTaskRules, duration_to_ns, rule as _rule

__all__ = ["ToAst"]

_ESCAPES = {"n": "\n", "t": "\t", "r": "\r", "\\": "\\", '"': '"', "0": "\0"}


def _unescape(literal: str) -> str:
    out, chars = [], iter(literal[1:-1])
    for char in chars:
        if char == "\\":
            nxt = next(chars, "")
            out.append(_ESCAPES.get(nxt, nxt))
        else:
            out.append(char)
    return "".join(out)


def _binary(op: str):
    @_rule
    def method(self, meta, left, right):
        return ast.Binary(op=op, left=left, right=right, loc=self.loc(meta))
    return method


def _f_unary(op: str, bounded: bool = False):
    if bounded:
        @_rule
        def method(self, meta, bounds, operand):
            return ast.FUnary(op=op, operand=operand, loc=self.loc(meta), bounds=bounds)
        return method

    @_rule
    def plain(self, meta, operand):
        return ast.FUnary(op=op, operand=operand, loc=self.loc(meta))
    return plain


def _f_binary(op: str, bounded: bool = False):
    if bounded:
        @_rule
        def method(self, meta, left, bounds, right):
            return ast.FBinary(op=op, left=left, right=right, loc=self.loc(meta),
                               bounds=bounds)
        return method

    @_rule
    def plain(self, meta, left, right):
        return ast.FBinary(op=op, left=left, right=right, loc=self.loc(meta))
    return plain


def _f_compare(op: str):
    @_rule
    def method(self, meta, left, right):
        return ast.FCompare(op=op, left=left, right=right, loc=self.loc(meta))
    return method


def _s_arith(op: str):
    @_rule
    def method(self, meta, left, right):
        return ast.SArith(op=op, left=left, right=right, loc=self.loc(meta))
    return method


def _f_predicate(predicate: str):
    @_rule
    def method(self, meta, name):
        return ast.FPredicate(predicate=predicate, argument=str(name), loc=self.loc(meta))
    return method


def _f_status(status: str):
    @_rule
    def method(self, meta):
        return ast.FStatus(status=status, loc=self.loc(meta))
    return method


def _simple(cls):
    @_rule
    def method(self, meta):
        return cls(loc=self.loc(meta))
    return method


def _opt(token: Token | None) -> str | None:
    return None if token is None else str(token)


class ToAst(RobotTaskRules, Transformer):
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
            from orccad_app.diagnostics import OrccadError
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

    # ------------------------------------------------------------------ expressions

    @_rule
    def name(self, meta, token):
        return ast.Name(name=str(token), loc=self.tloc(token))

    @_rule
    def number(self, meta, token):
        text = str(token)
        value = int(text) if token.type == "INT" else float(text)
        return ast.Number(value=value, text=text, loc=self.tloc(token))

    @_rule
    def duration(self, meta, token):
        return ast.DurationLit(duration_ns=self.ns(token), text=" ".join(str(token).split()),
                               loc=self.tloc(token))

    @_rule
    def string(self, meta, token):
        return ast.String(value=_unescape(str(token)), loc=self.tloc(token))

    @_rule
    def true(self, meta):
        return ast.Bool(value=True, loc=self.loc(meta))

    @_rule
    def false(self, meta):
        return ast.Bool(value=False, loc=self.loc(meta))

    @_rule
    def pi(self, meta):
        return ast.Number(value=math.pi, text="pi", loc=self.loc(meta))

    @_rule
    def last_value(self, meta, token):
        return ast.LastValue(signal=str(token), loc=self.loc(meta))

    @_rule
    def pre_signal(self, meta, token):
        return ast.PreSignal(signal=str(token), loc=self.loc(meta))

    @_rule
    def pre_value(self, meta, token):
        return ast.PreValue(signal=str(token), loc=self.loc(meta))

    @_rule
    def vector(self, meta, *items):
        items = () if items == (None,) else items
        return ast.Vector(items=tuple(items), loc=self.loc(meta))

    @_rule
    def call_expr(self, meta, name, args):
        return ast.Call(func=str(name), args=args, loc=self.loc(meta))

    @_rule
    def param_ref(self, meta, module, param):
        return ast.ParamRef(module=str(module), param=str(param), loc=self.loc(meta))

    @_rule
    def paren(self, meta, expr):
        return expr

    @_rule
    def neg(self, meta, operand):
        loc = self.loc(meta)
        if isinstance(operand, ast.Number) and operand.text[:1] != "-":
            return ast.Number(value=-operand.value, text="-" + operand.text, loc=loc)
        return ast.Unary(op="-", operand=operand, loc=loc)

    @_rule
    def not_(self, meta, operand):
        return ast.Unary(op="not", operand=operand, loc=self.loc(meta))

    or_, and_ = _binary("or"), _binary("and")
    lt, le, gt, ge, eq, ne = (_binary(op) for op in ("<", "<=", ">", ">=", "==", "!="))
    add, sub, mul, div = (_binary(op) for op in ("+", "-", "*", "/"))

    @_rule
    def call_args(self, meta, *args):
        return () if args == (None,) else tuple(args)

    @_rule
    def named_arg(self, meta, name, value):
        return ast.Arg(name=str(name), value=value, loc=self.loc(meta))

    @_rule
    def positional_arg(self, meta, value):
        return ast.Arg(name=None, value=value, loc=self.loc(meta))

    @_rule
    def call(self, meta, name, args):
        return ast.Call(func=str(name), args=args, loc=self.loc(meta))

    @_rule
    def observer(self, meta, name, args):
        return ast.Call(func=str(name), args=args or (), loc=self.loc(meta))

    @_rule
    def port_ref(self, meta, component, port):
        return ast.PortRef(component=str(component), port=str(port), loc=self.loc(meta))

    # ------------------------------------------------------------------ temporal logic

    @_rule
    def property_(self, meta, name, formula):
        mission, prop = name
        return ast.Property(mission=mission, name=prop, formula=formula, loc=self.loc(meta))

    @_rule
    def assume(self, meta, name, formula):
        mission, prop = name
        return ast.Assumption(mission=mission, name=prop, formula=formula, loc=self.loc(meta))

    @_rule
    def qualified_name(self, meta, mission, name):
        return (str(mission), str(name))

    @_rule
    def simple_name(self, meta, name):
        return (None, str(name))

    @_rule
    def f_signal(self, meta, token):
        return ast.FSignal(name=str(token), loc=self.tloc(token))

    @_rule
    def f_true(self, meta):
        return ast.FBool(value=True, loc=self.loc(meta))

    @_rule
    def f_false(self, meta):
        return ast.FBool(value=False, loc=self.loc(meta))

    @_rule
    def f_paren(self, meta, formula):
        return formula

    f_done, f_failed, f_aborted = (_f_status(s) for s in ("done", "failed", "aborted"))
    f_active, f_started, f_ended, f_raised = (
        _f_predicate(p) for p in ("active", "started", "ended", "raised"))
    f_not, f_next, f_previously = (_f_unary(op) for op in ("not", "next", "previously"))
    f_always, f_eventually, f_never, f_once, f_historically = (
        _f_unary(op, bounded=True) for op in ("always", "eventually", "never", "once",
                                              "historically"))
    f_iff, f_implies, f_or, f_and = (_f_binary(op) for op in ("<->", "->", "or", "and"))
    f_until, f_since = (_f_binary(op, bounded=True) for op in ("until", "since"))

    # ------------------------------------------------------------------ signal atoms (STL)

    f_lt, f_le, f_gt, f_ge = (_f_compare(op) for op in ("<", "<=", ">", ">="))
    s_add, s_sub, s_mul, s_div = (_s_arith(op) for op in "+-*/")

    @_rule
    def interval(self, meta, low, high):
        where = self.loc(meta)
        for bound in (low, high):
            if not math.isfinite(bound):
                raise OrccadError(f"time bound {bound} s is not finite", where)
        if low < 0:
            raise OrccadError(f"time bound {low:g} s is negative: write [a, b] with "
                              "0 <= a <= b", where)
        if high < low:
            raise OrccadError(f"empty time interval [{low:g}, {high:g}]: write [a, b] with "
                              "a <= b", where)
        return ast.Interval(low_s=low, high_s=high, loc=where)

    @_rule
    def s_bound(self, meta, token):
        if token.type == "DURATION":
            return duration_to_ns(str(token), self.tloc(token)) / 1e9
        return float(token)

    @_rule
    def s_port(self, meta, robot, port, index):
        return ast.SPort(robot=str(robot), port=str(port),
                         index=None if index is None else int(index), loc=self.loc(meta))

    @_rule
    def s_number(self, meta, token):
        value = float(token)
        if not math.isfinite(value):
            raise OrccadError(f"number {token} is not finite", self.tloc(token))
        return ast.SNumber(value=value, loc=self.tloc(token))

    @_rule
    def s_pi(self, meta):
        return ast.SNumber(value=math.pi, loc=self.loc(meta))

    @_rule
    def s_call(self, meta, func, *args):
        return ast.SCall(func=str(func), args=tuple(args), loc=self.loc(meta))

    @_rule
    def s_neg(self, meta, operand):
        return ast.SNeg(operand=operand, loc=self.loc(meta))

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
