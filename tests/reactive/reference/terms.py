"""The terms the reference rewrites besides the kernel's (:mod:`orccad_app.reactive.ir`): the
residuals of started statements, the derived forms, and the residuals of derived forms."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from orccad_app.reactive import ir

__all__ = ["Suspended", "Scoped", "Halt", "Sustain", "Await", "AwaitCount", "AwaitDuration",
           "Abort", "AbortCount", "SuspendNow", "LoopEach", "Every", "Repeat", "Race",
           "TrapHandle", "Waiting", "Counting", "Until", "Aborting", "AbortCounting",
           "Repeating", "NOTHING", "OUTERMOST"]

OUTERMOST = 10_000  # exit codes are 2 + OUTERMOST - (trap nesting depth)


@dataclass(frozen=True, slots=True, eq=False)
class Suspended:
    """``suspend body when test`` after its first instant: the test is now checked."""

    test: ir.Test
    body: ir.Stmt


@dataclass(frozen=True, slots=True, eq=False)
class Scoped:
    """The residual of ``signal … { body }``: ``bindings`` maps declarations to incarnations."""

    bindings: tuple[tuple[ir.SignalDecl, tuple], ...]
    body: ir.Stmt


# --------------------------------------------------------------------------- derived forms

def _node(name: str, *fields_: str, doc: str) -> type:
    """A frozen, identity-compared node class with positional ``fields_``."""
    namespace = {"__annotations__": {f: Any for f in fields_}, "__doc__": doc,
                 "__module__": __name__}
    return dataclass(frozen=True, slots=True, eq=False)(type(name, (), namespace))


Halt = _node("Halt", doc="``halt``: pauses forever")
Sustain = _node("Sustain", "signal", doc="``sustain S``: emits S in every instant, forever")
Await = _node("Await", "test", "immediate", doc="``await [immediate] t``")
AwaitCount = _node("AwaitCount", "count", "test", doc="``await n t``: n-th future instant of t")
AwaitDuration = _node("AwaitDuration", "duration", doc="``await d``: first instant past start+d")
Abort = _node("Abort", "body", "test", "weak", "immediate", "handler",
              doc="``[weak] abort body when [immediate] t [do handler]`` (handler may be None)")
AbortCount = _node("AbortCount", "body", "count", "test", "weak", "handler",
                   doc="``[weak] abort body when n t [do handler]``: the n-th later instant of t")
SuspendNow = _node("SuspendNow", "body", "test", doc="``suspend body when immediate t``")
LoopEach = _node("LoopEach", "body", "test", doc="``loop body each t``")
Every = _node("Every", "test", "body", "immediate", doc="``every [immediate] t do body``")
Repeat = _node("Repeat", "count", "body", doc="``repeat n times body``")
Race = _node("Race", "branches", doc="parallel branches; ends when the first one ends")
TrapHandle = _node("TrapHandle", "trap", "body", "handler", doc="``trap T body handle handler``")
# residuals of derived forms after their first instant
Waiting = _node("Waiting", "test", doc="``await t`` started: t is now tested")
Counting = _node("Counting", "test", "left", doc="``await n t`` with ``left`` occurrences to go")
Until = _node("Until", "deadline", doc="``await d`` started: waits for the clock")
Aborting = _node("Aborting", "body", "test", "weak", "handler", doc="``abort`` started")
AbortCounting = _node("AbortCounting", "body", "left", "test", "weak", "handler",
                      doc="counted ``abort`` started, ``left`` occurrences to go")
Repeating = _node("Repeating", "left", "current", "body",
                  doc="``repeat``: ``current`` runs, ``left`` more runs of ``body`` to go")

NOTHING = ir.Nothing()
