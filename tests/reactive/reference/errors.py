"""What stops the reference: errors of the program, incoherent instants, and the two
exceptions that abandon one execution (a status to guess, a value not known yet)."""

from __future__ import annotations

from orccad_app.reactive import ir

__all__ = ["ReferenceError_", "NotCoherent", "Pending", "Guess"]


class ReferenceError_(Exception):
    """A run-time error of the program (unset variable, instantaneous loop, bad exit)."""


class NotCoherent(Exception):
    """No or several coherent signal assignments: the instant is not logically correct."""

    def __init__(self, instant: int, solutions: list[dict]):
        self.instant = instant
        self.solutions = solutions
        shown = [{_key_name(k): v for k, v in s.items()} for s in solutions]
        super().__init__(f"instant {instant}: {len(solutions)} coherent assignments {shown}")


def _key_name(key) -> str:
    if isinstance(key, ir.SignalDecl):
        return key.name
    decl, instant, serial = key
    return f"{decl.name}#{instant}.{serial}"


class Pending(Exception):
    """A value read whose end-of-instant value is not known yet (see
    :class:`.reactor.ReferenceReactor`)."""


class Guess(Exception):
    """Execution needs the status of a signal incarnation the assumption does not give."""

    def __init__(self, key):
        self.key = key
