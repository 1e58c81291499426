"""The atoms of a mission's temporal properties and what each means in one instant.

One meaning, read by the model checker (:mod:`orccad_app.verify.letters`), its SPIN export
(:mod:`orccad_app.verify.promela`) and the run monitor
(:mod:`orccad_app.properties.recorder`): a proof and a run cannot read ``active(X)``
differently. An atom is a key, a tuple:

======================  =======================================================================
``("sig", S)``          input ``S`` present or output ``S`` emitted in the instant
``("started", X)``      Robot-Task X's start signal is emitted (an instance of X starts; its
                        :attr:`~.signals.RoleKind.START` signal, ``X.start``)
``("ended", X)``        X's good-end signal is emitted (:attr:`~.signals.RoleKind.GOOD_END`)
``("raised", E)``       exception E's raise signal is emitted (type 2 or 3,
                        :attr:`~.signals.RoleKind.RAISED`, ``E.raised``)
``("active", X)``       the state *after* the instant is inside an instance of X (it has an
                        ``RtLabel(X, site)``): true from the instant X starts, false from the
                        instant it ends, raises or is killed
``("status", s)``       the mission's status becomes ``s`` (``done``, ``failed``, ``aborted``)
                        in the instant
``("true",)``           every instant
======================  =======================================================================

The generated signals are found by their role (:class:`~.signals.SignalRoles`), never by
their names.
"""

from __future__ import annotations

from collections.abc import Callable, Collection, Iterable
from dataclasses import dataclass

from orccad_app.robottask.signals import RoleKind, SignalRoles

__all__ = ["Atoms", "InstantView", "SIGNAL", "STARTED", "ENDED", "RAISED", "ACTIVE", "STATUS",
           "TRUE_ATOM", "PREDICATES"]

SIGNAL = "sig"
STARTED = "started"
ENDED = "ended"
RAISED = "raised"
ACTIVE = "active"
STATUS = "status"
TRUE_ATOM = "true"

PREDICATES: dict[str, RoleKind] = {STARTED: RoleKind.START, ENDED: RoleKind.GOOD_END,
                                   RAISED: RoleKind.RAISED}
"""The predicates true when a generated signal of the role is emitted."""


@dataclass(frozen=True)
class InstantView:
    """What the atoms read of one instant.

    :param present: the inputs present and the outputs emitted in it.
    :param active: the Robot-Tasks active after it (called only when an ``active`` atom is
        asked for).
    :param status: the status the mission enters in it (``done``, ``failed``, ``aborted``, or
        another word for the checker's own instants), ``None`` when it does not change.
    """

    present: Collection[str]
    active: Callable[[], Collection[str]]
    status: str | None


class Atoms:
    """The meaning of ``keys`` in a mission whose generated signals have ``roles``."""

    def __init__(self, roles: SignalRoles, keys: Iterable[tuple]) -> None:
        self.keys: list[tuple] = sorted(set(keys))
        self._roles = roles
        self._signal = {key: self.signal(key) for key in self.keys}
        self.needs_active = any(key[0] == ACTIVE for key in self.keys)
        """Whether some key reads the active Robot-Tasks."""

    def signal(self, key: tuple) -> str | None:
        """The signal whose presence makes ``key`` true (``sig`` and the predicates of
        :data:`PREDICATES`); ``None`` for the other kinds, and for a predicate whose task
        or exception has no such signal in this mission (it is never true)."""
        kind = key[0]
        if kind == SIGNAL:
            return key[1]
        role = PREDICATES.get(kind)
        if role is None:
            return None
        for signal, found in self._roles.of_kind(role).items():
            if (found.name if role is RoleKind.RAISED else found.task) == key[1]:
                return signal
        return None

    def holds(self, key: tuple, instant: InstantView,
              active: Collection[str] | None = None) -> bool:
        """Whether ``key`` is true in ``instant`` (``active``: its active tasks, when the
        caller has them already)."""
        kind = key[0]
        if kind in (SIGNAL, STARTED, ENDED, RAISED):
            signal = self._signal[key] if key in self._signal else self.signal(key)
            return signal is not None and signal in instant.present
        if kind == ACTIVE:
            return key[1] in (instant.active() if active is None else active)
        if kind == STATUS:
            return instant.status == key[1]
        if kind == TRUE_ATOM:
            return True
        raise ValueError(f"unknown atom {key!r}")

    def letter(self, instant: InstantView) -> frozenset[tuple]:
        """The keys true in ``instant``."""
        active = instant.active() if self.needs_active else None
        return frozenset(key for key in self.keys if self.holds(key, instant, active))
