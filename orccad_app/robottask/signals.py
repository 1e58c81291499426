"""The role of every signal the Robot-Task lowering adds to a mission.

The lowering (:mod:`.rta`, :mod:`.application`) names the signals it makes (``X.start``,
``X.E.adjust``, ``E.raised``…); readers of the compiled automaton never parse those names
back: they look the role up in :class:`SignalRoles`, which the lowering fills as it makes them.
A signal without a role is one of the mission's own (declared inputs and outputs, and the
synchronization pre/post-conditions).
"""

from __future__ import annotations

import enum
from collections.abc import Iterable
from dataclasses import dataclass, field

from orccad_app.lang.ast_robottask import ExceptionType

__all__ = ["RoleKind", "SignalRole", "SignalRoles", "RaisedBy"]


class RoleKind(enum.Enum):
    """What a generated signal stands for."""

    START = "start"
    """Output ``X.start``: Robot-Task X is started (also on a restart)."""
    MEASURE = "measure"
    """Output ``X.measure``: X enters phase 2 (its measuring modules start)."""
    ACTIVATE = "activate"
    """Output ``X.activate``: X enters phase 3 (every module runs)."""
    GOOD_END = "good_end"
    """``X.good_end``: X ended normally (an output in the composed view, an input in the
    abstract one)."""
    EVENT = "event"
    """Input ``X.E``: the event of the observer serving condition or exception E of X (in the
    abstract view: X's outcome E)."""
    ADJUST = "adjust"
    """Output ``X.E.adjust``: apply the parameter update of X's type-1 exception E."""
    RAISED = "raised"
    """Output ``E.raised``: exception E (type 2 or 3) is raised, by a task or by ``within``."""
    ARGUMENT = "argument"
    """Valued output ``X.arg.P``: the value of X's parameter P, a run-time argument, in the
    instant X starts (:mod:`orccad_app.robottask.run_arguments`)."""


@dataclass(frozen=True)
class SignalRole:
    """The role of one signal.

    :param kind: what it stands for.
    :param task: the Robot-Task it belongs to (``None`` for :attr:`RoleKind.RAISED`).
    :param name: the exception or observer event it concerns (``EVENT``, ``ADJUST``,
        ``RAISED``), the parameter (``ARGUMENT``), else ``None``.
    """

    kind: RoleKind
    task: str | None = None
    name: str | None = None


@dataclass(frozen=True)
class RaisedBy:
    """A Robot-Task that can raise an exception into the application.

    :param task: the Robot-Task.
    :param type: abort, 2 (the task is killed, the application is told) or fatal, 3 (the application is
        aborted), RR-1801 §3.4.2; a watchdog's ``OBSERVER_timeout`` is type 2.
    """

    task: str
    type: ExceptionType


@dataclass
class SignalRoles:
    """Signal name -> role, and who can raise each exception.

    :param by_signal: the role of every generated signal.
    :param raisers: exception name -> the tasks that can raise it, in declaration order
        (``Timeout`` of ``run … within`` has none: the mission raises it).
    """

    by_signal: dict[str, SignalRole] = field(default_factory=dict)
    raisers: dict[str, list[RaisedBy]] = field(default_factory=dict)

    def add(self, signal: str, kind: RoleKind, task: str | None = None,
            name: str | None = None) -> None:
        """Record the role of ``signal``."""
        self.by_signal[signal] = SignalRole(kind, task, name)

    def add_raiser(self, exception: str, task: str, type_: ExceptionType) -> None:
        """Record that ``task`` can raise ``exception`` with type ``type_``."""
        found = self.raisers.setdefault(exception, [])
        if all(r.task != task for r in found):
            found.append(RaisedBy(task, type_))

    def get(self, signal: str) -> SignalRole | None:
        """The role of ``signal``; ``None`` for the mission's own signals."""
        return self.by_signal.get(signal)

    def is_own(self, signal: str) -> bool:
        """Whether ``signal`` is one of the mission's own (declared, or a synchronization
        condition) rather than one the lowering added."""
        return signal not in self.by_signal

    def own(self, signals: Iterable[str]) -> list[str]:
        """The mission's own among ``signals``, in their order."""
        return [signal for signal in signals if signal not in self.by_signal]

    def of_kind(self, kind: RoleKind) -> dict[str, SignalRole]:
        """Signal -> role, for the signals of role ``kind``."""
        return {signal: role for signal, role in self.by_signal.items() if role.kind is kind}

    def raised_exceptions(self) -> list[str]:
        """The exceptions the mission can raise (type 2 or 3: an ``E.raised`` signal), by
        name."""
        return sorted(role.name for role in self.by_signal.values()
                      if role.kind is RoleKind.RAISED and role.name is not None)

    def signal(self, kind: RoleKind, task: str) -> str | None:
        """The signal of role ``kind`` of ``task`` (e.g. its ``START``), if it has one."""
        for signal, role in self.by_signal.items():
            if role.kind is kind and role.task == task:
                return signal
        return None
