"""Transformer rules for ``robottask`` blocks, and duration literals.

A mixin of :class:`orccad_app.lang.transform.ToAst`: each Robot-Task item becomes a tagged
tuple, then :meth:`RobotTaskRules.robottask` groups them into one :class:`~.ast.RobotTask`,
rejecting duplicates (two ``law`` lines, two ``period`` clauses...).
"""

from __future__ import annotations

import difflib
from decimal import Decimal

from lark import Token, v_args

from orccad_app.diagnostics import NOWHERE, OrccadError, SourceLocation
from orccad_app.lang import ast

__all__ = ["RobotTaskRules", "duration_to_ns", "UNIT_NS", "rule"]

#: Nanoseconds per duration unit.
UNIT_NS: dict[str, int] = {"s": 1_000_000_000, "ms": 1_000_000, "us": 1_000, "ns": 1}

#: Decorator of every transformer rule method: ``method(self, meta, *children)``.
rule = v_args(inline=True, meta=True)

_SINGLE_ITEMS = ("duration", "task_function", "law", "automaton")


def duration_to_ns(text: str, location: SourceLocation = NOWHERE) -> int:
    """``"2.5 s"`` → ``2_500_000_000``; the value must be a whole number of nanoseconds."""
    body = text.rstrip()
    unit = next(u for u in ("ms", "us", "ns", "s") if body.endswith(u))
    value = Decimal(body[: -len(unit)].strip()) * UNIT_NS[unit]
    if value != value.to_integral_value():
        raise OrccadError(f"duration '{' '.join(text.split())}' is not a whole number of "
                          "nanoseconds", location)
    return int(value)


def _check_protocol(token: Token, location: SourceLocation) -> str:
    name = str(token)
    if name in ast.PROTOCOLS:
        return name
    close = difflib.get_close_matches(name, ast.PROTOCOLS, n=1, cutoff=0.6)
    hint = f"; did you mean '{close[0]}'?" if close else f" (one of {', '.join(ast.PROTOCOLS)})"
    raise OrccadError(f"unknown protocol '{name}'{hint}", location)


class RobotTaskRules:
    """Rules of the ``robottask`` part of the grammar (needs ``loc``/``tloc``/``ns``)."""

    @rule
    def param(self, meta, name, type_, default):
        return ast.Param(name=str(name), type=None if type_ is None else str(type_),
                         default=default, loc=self.loc(meta))

    @rule
    def rt_duration(self, meta, token):
        return ("duration", self.ns(token), self.loc(meta))

    @rule
    def rt_task_function(self, meta, call):
        return ("task_function", call, self.loc(meta))

    @rule
    def rt_law(self, meta, call):
        return ("law", call, self.loc(meta))

    @rule
    def rt_automaton(self, meta, processor, reaction):
        loc = self.loc(meta)
        placement = ast.AutomatonPlacement(processor=str(processor),
                                           reaction_ns=0 if reaction is None else self.ns(reaction),
                                           loc=loc)
        return ("automaton", placement, loc)

    @rule
    def rt_module(self, meta, name, kind, args, *clauses):
        timing: dict[str, object] = {}
        for key, value, loc in clauses:
            if key in timing:
                raise OrccadError(f"duplicate '{key.removesuffix('_ns')}' in module "
                                  f"'{name}'", loc)
            timing[key] = value
        module = ast.Module(name=str(name), kind=str(kind), args=args or (),
                            loc=self.loc(meta), **timing)
        return ("modules", module, module.loc)

    @rule
    def clause_period(self, meta, token):
        return ("period_ns", self.ns(token), self.loc(meta))

    @rule
    def clause_wcet(self, meta, token):
        return ("wcet_ns", self.ns(token), self.loc(meta))

    @rule
    def clause_bcet(self, meta, token):
        return ("bcet_ns", self.ns(token), self.loc(meta))

    @rule
    def clause_on(self, meta, token):
        return ("processor", str(token), self.loc(meta))

    @rule
    def clause_priority(self, meta, token):
        return ("priority", int(token), self.loc(meta))

    @rule
    def clause_sporadic(self, meta, token):
        return ("min_interarrival_ns", self.ns(token), self.loc(meta))

    @rule
    def rt_connect(self, meta, source, target, protocol):
        name = ast.DEFAULT_PROTOCOL if protocol is None else _check_protocol(
            protocol, self.tloc(protocol))
        connect = ast.Connect(source=source, target=target, protocol=name, loc=self.loc(meta))
        return ("connections", connect, connect.loc)

    @rule
    def rt_pre_signal(self, meta, name):
        node = ast.SignalPrecondition(signal=str(name), loc=self.loc(meta))
        return ("preconditions", node, node.loc)

    @rule
    def rt_pre_measure(self, meta, observer, within):
        node = ast.MeasurePrecondition(
            observer=observer, within_ns=None if within is None else self.ns(within),
            loc=self.loc(meta))
        return ("preconditions", node, node.loc)

    @rule
    def rt_exception(self, meta, name, source, kind):
        type_, adjust = kind
        node = ast.ExceptionDecl(name=str(name), source=source, type=type_, adjust=adjust,
                                 loc=self.loc(meta))
        return ("exceptions", node, node.loc)

    @rule
    def exc_fatal(self, meta):
        return (ast.ExceptionType.FATAL, None)

    @rule
    def exc_abort(self, meta):
        return (ast.ExceptionType.ABORT, None)

    @rule
    def exc_adjust(self, meta, target, value):
        return (ast.ExceptionType.ADJUST,
                ast.Adjust(target=target, value=value, loc=self.loc(meta)))

    @rule
    def rt_post_measure(self, meta, observer):
        node = ast.MeasurePostcondition(observer=observer, loc=self.loc(meta))
        return ("postconditions", node, node.loc)

    @rule
    def rt_post_emit(self, meta, name):
        node = ast.SignalPostcondition(signal=str(name), loc=self.loc(meta))
        return ("postconditions", node, node.loc)

    @rule
    def robottask(self, meta, name, *rest):
        params = [p for p in rest if isinstance(p, ast.Param)]
        robot = next(t for t in rest if isinstance(t, Token))
        items = [i for i in rest if isinstance(i, tuple)]
        fields: dict[str, object] = {}
        groups: dict[str, list] = {}
        for key, value, loc in items:
            if key in _SINGLE_ITEMS:
                if key in fields:
                    raise OrccadError(f"duplicate '{key}' in robottask '{name}'", loc)
                fields[key] = value
            else:
                groups.setdefault(key, []).append(value)
        if "duration" in fields:
            fields["duration_ns"] = fields.pop("duration")
        return ast.RobotTask(name=str(name), params=tuple(params), robot=str(robot),
                             loc=self.loc(meta), **fields,
                             **{k: tuple(v) for k, v in groups.items()})
