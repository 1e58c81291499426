"""Derived statements, expanded into the kernel as Esterel v5 expands them.

Each function returns kernel IR (:mod:`orccad_app.reactive.ir`). Where an expansion needs a
fresh trap or a hidden variable it makes a new declaration, so expansions never capture the
user's names. Counters (``await 3 S``, ``repeat``) and timers (``await 2 s``, ``every 1 s``) are
hidden data variables, never states.

==========================  ==================================================================
``halt``                    ``loop pause``
``sustain S``               ``loop { emit S; pause }``
``await S``                 ``trap T { loop { pause; present S { exit T } } }``
``await immediate S``       ``trap T { loop { present S { exit T }; pause } }``
``await n S``               ``c := n; trap T { loop { pause; present S { c := c-1;``
                            `` if c <= 0 { exit T } } } }``
``await d`` (duration)      ``t := clock + d; trap T { loop { pause; if clock >= t { exit T } } }``
``abort p when S``          ``trap T { { suspend p when S; exit T } || { await S; exit T } }``
``weak abort p when S``     ``trap T { { p; exit T } || { await S; exit T } }``
``… when S do q``           ``trap D { trap T { { …; exit D } || { await S; exit T } }; q }``
``suspend immediate``       ``await immediate not S; suspend p when S``
``abort p when n S``        ``signal R { trap D { { abort p when R; exit D } || { await n S; emit R; halt } } }``
``loop p each S``           ``loop { abort { p; halt } when S }``
``every S p``               ``await S; loop { abort { p; halt } when S }``
``every d p``               periodic deadlines ``t := t + d`` anchored at the start
``repeat n p``              ``c := n; trap T { loop { if c <= 0 { exit T }; c := c-1; p } }``
``trap T p handle q``       ``trap D { trap T { p; exit D }; q }``
``race p || q``             ``trap T { { p; exit T } || { q; exit T } }``
==========================  ==================================================================
"""

from __future__ import annotations

from orccad_app.diagnostics import NOWHERE, SourceLocation
from orccad_app.reactive import ir

__all__ = [
    "seq", "halt", "sustain", "await_signal", "await_count", "await_duration", "abort",
    "suspend", "loop_each", "every_signal", "every_duration", "repeat", "trap_handle", "race",
    "deadline", "abort_count",
]


def seq(*items: ir.Stmt, loc: SourceLocation = NOWHERE) -> ir.Stmt:
    """A sequence, flattening nested sequences and dropping ``nothing``."""
    flat: list[ir.Stmt] = []
    for item in items:
        if isinstance(item, ir.Seq):
            flat.extend(item.items)
        elif not isinstance(item, ir.Nothing):
            flat.append(item)
    if not flat:
        return ir.Nothing(loc)
    if len(flat) == 1:
        return flat[0]
    return ir.Seq(tuple(flat), loc)


def halt(loc: SourceLocation = NOWHERE) -> ir.Stmt:
    return ir.Loop(ir.Pause(loc), loc, "halt")


def sustain(signal: ir.SignalDecl, value: ir.Expr | None = None,
            loc: SourceLocation = NOWHERE) -> ir.Stmt:
    return ir.Loop(seq(ir.Emit(signal, value, loc), ir.Pause(loc)), loc, "sustain")


def _trap(name: str, loc: SourceLocation) -> ir.TrapDecl:
    return ir.TrapDecl(f"_{name}", loc)


def await_signal(test: ir.Test, *, immediate: bool = False,
                 loc: SourceLocation = NOWHERE) -> ir.Stmt:
    """Terminates at the next instant where ``test`` holds (or this one if ``immediate``)."""
    done = _trap("await", loc)
    check = ir.Present(test, ir.Exit(done, loc), ir.Nothing(loc), loc)
    body = seq(check, ir.Pause(loc)) if immediate else seq(ir.Pause(loc), check)
    return ir.Trap(done, ir.Loop(body, loc, "await"), loc)


def await_count(count: ir.Expr, test: ir.Test, loc: SourceLocation = NOWHERE) -> ir.Stmt:
    """``await n S``: the n-th future instant where ``test`` holds; ``n`` is read at start."""
    counter = ir.VarDecl("_count", loc, hidden=True)
    done = _trap("await", loc)
    decrement = ir.Assign(counter, ir.Binary("-", ir.VarRef(counter, loc), ir.Const(1, loc), loc), loc)
    reached = ir.DataTest(ir.Binary("<=", ir.VarRef(counter, loc), ir.Const(0, loc), loc), loc)
    on_occurrence = seq(decrement, ir.Present(reached, ir.Exit(done, loc), ir.Nothing(loc), loc))
    body = seq(ir.Pause(loc), ir.Present(test, on_occurrence, ir.Nothing(loc), loc))
    return seq(ir.Assign(counter, count, loc), ir.Trap(done, ir.Loop(body, loc, "await"), loc))


def _deadline_reached(deadline: ir.VarDecl, loc: SourceLocation) -> ir.Test:
    return ir.DataTest(ir.Binary(">=", ir.Clock(loc), ir.VarRef(deadline, loc), loc), loc)


def deadline(duration_ns: ir.Expr, loc: SourceLocation = NOWHERE,
             name: str = "_deadline") -> tuple[ir.VarDecl, ir.Stmt, ir.Test]:
    """A timer: (its hidden variable, ``t := clock + duration`` to start it, ``clock >= t``)."""
    var = ir.VarDecl(name, loc, hidden=True)
    start = ir.Assign(var, ir.Binary("+", ir.Clock(loc), duration_ns, loc), loc)
    return var, start, _deadline_reached(var, loc)


def await_duration(duration_ns: ir.Expr, loc: SourceLocation = NOWHERE) -> ir.Stmt:
    """Terminates at the first later instant whose clock has reached start + duration."""
    _, start, reached = deadline(duration_ns, loc)
    return seq(start, await_signal(reached, loc=loc))


def abort(body: ir.Stmt, test: ir.Test, *, weak: bool = False, immediate: bool = False,
          handler: ir.Stmt | None = None, loc: SourceLocation = NOWHERE) -> ir.Stmt:
    """Strong (default) or weak preemption of ``body`` by ``test``, with an optional handler."""
    aborted = _trap("abort", loc)
    finished = _trap("abort_done", loc) if handler is not None else aborted
    guarded = body if weak else suspend(body, test, immediate=immediate, loc=loc)
    watcher = seq(await_signal(test, immediate=immediate, loc=loc), ir.Exit(aborted, loc))
    inner = ir.Trap(aborted, ir.Par((seq(guarded, ir.Exit(finished, loc)), watcher), loc), loc)
    if handler is None:
        return inner
    return ir.Trap(finished, seq(inner, handler), loc)


def abort_count(body: ir.Stmt, count: ir.Expr, test: ir.Test, *, weak: bool = False,
                handler: ir.Stmt | None = None, loc: SourceLocation = NOWHERE) -> ir.Stmt:
    """``[weak] abort body when n S``: a watcher counts the occurrences of the test (as
    ``await n S``) and emits a hidden local signal that preempts the body."""
    reached = ir.SignalDecl("_counted", ir.LOCAL, None, loc)
    watcher = seq(await_count(count, test, loc), ir.Emit(reached, None, loc), halt(loc))
    done = _trap("counted_done", loc)
    preempted = abort(body, ir.SigRef(reached, loc), weak=weak, handler=handler, loc=loc)
    return ir.Local((reached,), ir.Trap(done, ir.Par(
        (seq(preempted, ir.Exit(done, loc)), watcher), loc), loc), loc)


def suspend(body: ir.Stmt, test: ir.Test, *, immediate: bool = False,
            loc: SourceLocation = NOWHERE) -> ir.Stmt:
    frozen = ir.Suspend(test, body, loc)
    if not immediate:
        return frozen
    return seq(await_signal(ir.SigNot(test, loc), immediate=True, loc=loc), frozen)


def loop_each(body: ir.Stmt, test: ir.Test, loc: SourceLocation = NOWHERE) -> ir.Stmt:
    return ir.Loop(abort(seq(body, halt(loc)), test, loc=loc), loc, "loop … each")


def every_signal(test: ir.Test, body: ir.Stmt, *, immediate: bool = False,
                 loc: SourceLocation = NOWHERE) -> ir.Stmt:
    return seq(await_signal(test, immediate=immediate, loc=loc), loop_each(body, test, loc))


def every_duration(period_ns: ir.Expr, body: ir.Stmt, loc: SourceLocation = NOWHERE) -> ir.Stmt:
    """Starts ``body`` every ``period_ns`` from the start, killing the previous run."""
    timer, start, reached = deadline(period_ns, loc)
    advance = ir.Assign(timer, ir.Binary("+", ir.VarRef(timer, loc), period_ns, loc), loc)
    run_once = seq(advance, abort(seq(body, halt(loc)), reached, loc=loc))
    return seq(start, await_signal(reached, loc=loc), ir.Loop(run_once, loc, "every"))


def repeat(count: ir.Expr, body: ir.Stmt, loc: SourceLocation = NOWHERE) -> ir.Stmt:
    counter = ir.VarDecl("_repeat", loc, hidden=True)
    done = _trap("repeat", loc)
    finished = ir.DataTest(ir.Binary("<=", ir.VarRef(counter, loc), ir.Const(0, loc), loc), loc)
    decrement = ir.Assign(counter, ir.Binary("-", ir.VarRef(counter, loc), ir.Const(1, loc), loc), loc)
    loop_body = seq(ir.Present(finished, ir.Exit(done, loc), ir.Nothing(loc), loc), decrement, body)
    return seq(ir.Assign(counter, count, loc), ir.Trap(done, ir.Loop(loop_body, loc, "repeat"), loc))


def trap_handle(trap: ir.TrapDecl, body: ir.Stmt, handler: ir.Stmt | None,
                loc: SourceLocation = NOWHERE) -> ir.Stmt:
    if handler is None:
        return ir.Trap(trap, body, loc)
    finished = _trap("trap_done", loc)
    return ir.Trap(finished, seq(ir.Trap(trap, seq(body, ir.Exit(finished, loc)), loc), handler), loc)


def race(branches: tuple[ir.Stmt, ...], loc: SourceLocation = NOWHERE) -> ir.Stmt:
    first = _trap("race", loc)
    return ir.Trap(first, ir.Par(tuple(seq(b, ir.Exit(first, loc)) for b in branches), loc), loc)
