"""What the user raises during a live run, delivered exactly as ``orccad run --inject`` does.

The console's keys are pressed on the UI's thread at a wall-clock moment; the run is at some
simulated instant ``t`` then. :class:`UserInputs` queues each request, and at the automaton's
next reaction (on the executive's thread) schedules it as a kernel event at the **due
instant** :func:`due_ns` — the second reaction tick after ``t`` — the very event
``--inject NAME@T`` schedules:

- a **pulse** raises the input at ``T``: it joins the tick's reaction there (no reaction is
  added: the run is the one ``orccad run … --inject NAME@T`` gives, bit for bit);
- a **plant fault** is applied to the robot's plant at ``T`` (``--inject ROBOT.FAULT=V@T``);
- a **hold** raises the input at every tick from its due instant until the due instant of its
  release (``--inject NAME@T`` for each of those ticks), re-scheduling itself one tick ahead;
  it is reported as **one** record (first and last instant, how many instants), not one per
  instant.

Why the second tick: the next tick's event is already in the kernel's queue when the reaction
at ``t`` runs, and an injection queued after it at the same instant would make a second
reaction there; the tick after that is scheduled only later, so an injection scheduled now
precedes it, as ``--inject``'s events (scheduled before the run) precede every tick.
"""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass
from typing import Any, Callable

from orccad_app.diagnostics import OrccadError
from orccad_app.executive.kernel import EventClass
from orccad_app.mission.injection import PlantFault
from orccad_app.trace.report import InjectionRecord

__all__ = ["UserInputs", "due_ns", "HELD_BY", "RAISED_BY"]

RAISED_BY = "user"
"""Who raised a pulse or a fault, in the report."""
HELD_BY = "user (held)"
"""Who held an input, in the report."""


def due_ns(t_ns: int, tick_ns: int) -> int:
    """The instant [ns] at which a request made during the reaction at ``t_ns`` takes effect:
    the second tick after ``t_ns`` (see the module docstring)."""
    return (t_ns // tick_ns + 2) * tick_ns


@dataclass
class _Hold:
    """One hold of input ``name``: raised at every tick from ``first_ns`` until ``until_ns``
    (excluded; ``None`` while not released)."""

    name: str
    value: Any
    first_ns: int
    until_ns: int | None = None
    last_ns: int = -1
    instants: int = 0

    def record(self) -> InjectionRecord:
        return InjectionRecord(self.first_ns, self.name, self.value, False, HELD_BY,
                               until_ns=self.last_ns, instants=self.instants)


def _shown(name: str, value: Any) -> str:
    return name if value is None else f"{name}({value})"


class UserInputs:
    """The user's requests of one run (see the module docstring).

    :param run: the :class:`~orccad_app.mission.run.MissionRun`.
    :param log: called on the executive's thread with ``(time [ns], kind, text)`` of each
        input, hold and fault when it takes effect.
    """

    def __init__(self, run: Any, log: Callable[[int, str, str], None]) -> None:
        self.run, self.log = run, log
        self._queue: deque[tuple[str, str, Any]] = deque()
        self._held: dict[str, Any] = {}
        self._holds: dict[str, _Hold] = {}
        self._records: list[InjectionRecord] = []
        self._ended: list[_Hold] = []

    # -- from the UI's thread --------------------------------------------------------------

    def pulse(self, name: str, value: Any = None) -> None:
        """Raise input ``name`` once (at the due instant)."""
        self._queue.append(("pulse", name, value))

    def fault(self, name: str, value: Any) -> None:
        """Apply plant fault ``ROBOT.FAULT`` with ``value`` (at the due instant); a value out
        of the fault's declared range raises :class:`OrccadError` now, as ``--inject``
        refuses it."""
        self.check_fault(name, value)
        self._queue.append(("fault", name, value))

    def check_fault(self, name: str, value: Any) -> None:
        """Raise :class:`OrccadError` unless ``ROBOT.FAULT`` is a fault of a robot of the run
        and ``value`` within its declared range."""
        fault = _plant_fault(name)
        self.run.check_fault(fault.robot, fault.fault, value)

    def hold(self, name: str, value: Any = None) -> None:
        """Raise input ``name`` at every tick from the due instant until :meth:`release`."""
        if name not in self._held:
            self._held[name] = value
            self._queue.append(("hold", name, value))

    def release(self, name: str) -> None:
        """Stop holding input ``name`` (from the due instant of the release)."""
        if name in self._held:
            del self._held[name]
            self._queue.append(("release", name, None))

    @property
    def held(self) -> tuple[str, ...]:
        """The inputs held now (as the user set them)."""
        return tuple(self._held)

    # -- on the executive's thread -----------------------------------------------------------

    def on_reaction(self, t_ns: int) -> None:
        """Schedule what was requested since the last reaction at its due instant."""
        if not self._queue:
            return
        due = due_ns(t_ns, self.run.tick_ns)
        schedule = self.run.kernel.schedule
        while self._queue:
            what, name, value = self._queue.popleft()
            if what == "pulse":
                schedule(due, EventClass.CONTROL, self._pulse, (name, value))
            elif what == "fault":
                schedule(due, EventClass.CONTROL, self._fault, (name, value))
            elif what == "hold":
                hold = _Hold(name, value, due)
                self._holds[name] = hold
                schedule(due, EventClass.CONTROL, self._hold_tick, hold)
            elif name in self._holds:  # release
                self._holds.pop(name).until_ns = due

    def _pulse(self, item: tuple[str, Any]) -> None:
        name, value = item
        now = self.run.kernel.now
        self.run.inject(name, value)
        self._records.append(InjectionRecord(now, name, value, False, RAISED_BY))
        self.log(now, "input", f"{_shown(name, value)} raised by the user")

    def _fault(self, item: tuple[str, Any]) -> None:
        name, value = item
        now = self.run.kernel.now
        fault = _plant_fault(name)
        self.run.apply_fault(fault.robot, fault.fault, value)
        self._records.append(InjectionRecord(now, name, value, True, RAISED_BY))
        self.log(now, "fault", f"{name}={value} injected by the user")

    def _hold_tick(self, hold: _Hold) -> None:
        now = self.run.kernel.now
        if hold.until_ns is not None and now >= hold.until_ns:
            self._ended.append(hold)
            span = (f"{hold.first_ns / 1e9:.3f}–{hold.last_ns / 1e9:.3f} s, "
                    f"{hold.instants} instants" if hold.instants else "no instant")
            self.log(now, "input", f"{hold.name} released by the user (held {span})")
            return
        self.run.inject(hold.name, hold.value)
        hold.instants += 1
        hold.last_ns = now
        if hold.instants == 1:
            self.log(now, "input", f"{_shown(hold.name, hold.value)} held by the user")
        self.run.kernel.schedule(now + self.run.tick_ns, EventClass.CONTROL, self._hold_tick,
                                 hold)

    def records(self) -> list[InjectionRecord]:
        """Everything raised so far, in time order: one record per pulse and fault, one per
        hold (its first and last instant, still open ones up to now)."""
        holds = [*self._ended, *self._holds.values()]
        found = self._records + [h.record() for h in holds if h.instants]
        return sorted(found, key=lambda record: (record.time_ns, record.name))


def _plant_fault(name: str) -> PlantFault:
    """The fault ``ROBOT.FAULT`` the console lists as ``name`` (its robot and fault, typed)."""
    fault = PlantFault.named(name)
    if fault is None:
        raise OrccadError(f"'{name}' is not a plant fault (ROBOT.FAULT)")
    return fault
