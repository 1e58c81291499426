"""The rewriting rules of the derived forms (:mod:`.terms`), from their Esterel v5 meaning.

:class:`DerivedForms` is mixed into :class:`.run.Run`: its rules use the run's ``react``,
``holds``, ``value``, ``memory`` and ``_suspend_body``.
"""

from __future__ import annotations

from orccad_app.reactive import ir
from tests.reactive.reference.errors import ReferenceError_
from tests.reactive.reference.terms import (
    NOTHING, OUTERMOST, Abort, AbortCounting, Aborting, Await, Counting, Halt, LoopEach, Race,
    Repeating, TrapHandle, Until, Waiting,
)

__all__ = ["DerivedForms"]


class DerivedForms:
    """The derived forms' rules of :class:`.run.Run` (one method per node class)."""

    def _halt(self, term, scope, traps):
        return 1, term

    def _sustain(self, term, scope, traps):
        self.emitted.add(scope.get(term.signal, term.signal))
        return 1, term

    def _await(self, term, scope, traps):
        if term.immediate and self.holds(term.test, scope):
            return 0, NOTHING
        return 1, Waiting(term.test)

    def _waiting(self, term, scope, traps):
        return (0, NOTHING) if self.holds(term.test, scope) else (1, term)

    def _await_count(self, term, scope, traps):
        return 1, Counting(term.test, self.value(term.count, scope))

    def _counting(self, term, scope, traps):
        if not self.holds(term.test, scope):
            return 1, term
        return (0, NOTHING) if term.left <= 1 else (1, Counting(term.test, term.left - 1))

    def _await_duration(self, term, scope, traps):
        return 1, Until(self.memory.clock_ns + self.value(term.duration, scope))

    def _until(self, term, scope, traps):
        return (0, NOTHING) if self.memory.clock_ns >= term.deadline else (1, term)

    def _abort(self, term, scope, traps):
        strong_now = term.immediate and not term.weak
        if strong_now and self.holds(term.test, scope):
            return self._aborted(term.handler, scope, traps)
        return self._abort_body(term.body, term, term.weak and term.immediate, scope, traps)

    def _aborting(self, term, scope, traps):
        if not term.weak and self.holds(term.test, scope):
            return self._aborted(term.handler, scope, traps)
        return self._abort_body(term.body, term, term.weak, scope, traps)

    def _abort_body(self, body, term, test_after: bool, scope, traps):
        """The body reacts; a weak abort then tests its condition (the body had its say)."""
        code, residual = self.react(body, scope, traps)
        if code != 1:
            return code, NOTHING
        if test_after and self.holds(term.test, scope):
            return self._aborted(term.handler, scope, traps)
        return 1, Aborting(residual, term.test, term.weak, term.handler)

    def _aborted(self, handler, scope, traps):
        return (0, NOTHING) if handler is None else self.react(handler, scope, traps)

    def _abort_count(self, term, scope, traps):
        left = self.value(term.count, scope)
        return self._count_body(term.body, term, left, False, scope, traps)

    def _abort_counting(self, term, scope, traps):
        left, fired = term.left, False
        if self.holds(term.test, scope):
            left -= 1
            fired = left <= 0
        if fired and not term.weak:
            return self._aborted(term.handler, scope, traps)
        return self._count_body(term.body, term, left, fired, scope, traps)

    def _count_body(self, body, term, left, fired, scope, traps):
        """The body reacts; a weak counted abort whose count is reached then dies."""
        code, residual = self.react(body, scope, traps)
        if code != 1:
            return code, NOTHING
        if fired:
            return self._aborted(term.handler, scope, traps)
        return 1, AbortCounting(residual, left, term.test, term.weak, term.handler)

    def _mark(self, term, scope, traps):
        return self.react(term.body, scope, traps)

    def _suspend_now(self, term, scope, traps):
        if self.holds(term.test, scope):
            return 1, term  # not started yet
        return self._suspend_body(term.test, term.body, scope, traps)

    def _loop_each(self, term, scope, traps):
        body = Abort(ir.Seq((term.body, Halt())), term.test, False, False, None)
        return self.react(ir.Loop(body, what="loop … each"), scope, traps)

    def _every(self, term, scope, traps):
        start = Await(term.test, term.immediate)
        return self.react(ir.Seq((start, LoopEach(term.body, term.test))), scope, traps)

    def _repeat(self, term, scope, traps):
        return self._repeat_from(self.value(term.count, scope), term.body, scope, traps)

    def _repeating(self, term, scope, traps):
        code, residual = self.react(term.current, scope, traps)
        if code == 0:
            return self._repeat_from(term.left, term.body, scope, traps)
        return code, (Repeating(term.left, residual, term.body) if code == 1 else NOTHING)

    def _repeat_from(self, left, body, scope, traps):
        if left <= 0:
            return 0, NOTHING
        code, residual = self.react(body, scope, traps)
        if code == 0:
            raise ReferenceError_("instantaneous repeat body")
        return code, (Repeating(left - 1, residual, body) if code == 1 else NOTHING)

    def _race(self, term, scope, traps):
        results = [self.react(branch, scope, traps) for branch in term.branches]
        code = max(c for c, _ in results)
        if code >= 2:
            return code, NOTHING
        if any(c == 0 for c, _ in results):
            return 0, NOTHING
        return 1, Race(tuple(r for _, r in results))

    def _trap_handle(self, term, scope, traps):
        own = 2 + OUTERMOST - len(traps)
        code, residual = self.react(term.body, scope, (*traps, term.trap))
        if code == own:
            return self._aborted(term.handler, scope, traps)
        if code == 1:
            return 1, TrapHandle(term.trap, residual, term.handler)
        return code, NOTHING
