"""Observing a simulation without reaching into it (py_trees-style visitors).

Subclass :class:`Observer` and override the callbacks you need; pass instances to
:class:`~orccad_app.executive.simulation.Simulation` (``observers=[...]``) or
:meth:`~orccad_app.executive.simulation.Simulation.add_observer`. Each callback is called at the
simulated instant ``t_ns`` when the thing happens, in event order; only overridden callbacks are
called (the executive precomputes who listens, so unused hooks cost nothing). Callbacks must not
mutate the values they are given; they may call the simulation's control methods
(``activate``, ``kill``, ``set_param``), which take effect in the same instant, after the
current event.
"""

from __future__ import annotations

from typing import Any

__all__ = ["Observer", "EventLog", "HOOKS", "listeners"]

HOOKS = (
    "on_release", "on_start", "on_preempt", "on_resume", "on_compute_end", "on_finish",
    "on_overrun", "on_block", "on_unblock", "on_read", "on_write", "on_signal", "on_message",
    "on_activate", "on_kill", "on_param", "on_deadlock",
)
"""Names of every callback, in the order they are documented."""


class Observer:
    """Callbacks of the executive; every default does nothing."""

    def on_release(self, t_ns: int, module: str, job: int) -> None:
        """Job number ``job`` (0-based) of ``module`` is released."""

    def on_start(self, t_ns: int, module: str, job: int, processor: str) -> None:
        """The job first gets its processor; its ``compute`` runs now."""

    def on_preempt(self, t_ns: int, module: str, job: int, processor: str) -> None:
        """The running job loses its processor to a more urgent one."""

    def on_resume(self, t_ns: int, module: str, job: int, processor: str) -> None:
        """A preempted job gets its processor back."""

    def on_compute_end(self, t_ns: int, module: str, job: int, processor: str) -> None:
        """The job's execution time is consumed; it now writes its outputs."""

    def on_finish(self, t_ns: int, module: str, job: int, response_ns: int,
                  missed: bool) -> None:
        """Every output is written; ``missed`` when after the absolute deadline."""

    def on_overrun(self, t_ns: int, module: str, job: int) -> None:
        """A release is skipped because job ``job`` is still unfinished (a deadline miss)."""

    def on_block(self, t_ns: int, module: str, port: str, operation: str,
                 protocol: str) -> None:
        """A ``read``/``write`` on ``module.port`` blocks under ``protocol``."""

    def on_unblock(self, t_ns: int, module: str, port: str, operation: str,
                   blocked_ns: int) -> None:
        """The blocked operation completes after ``blocked_ns``."""

    def on_read(self, t_ns: int, module: str, port: str, value: Any) -> None:
        """``module`` read ``value`` on its input ``port``."""

    def on_write(self, t_ns: int, module: str, port: str, value: Any) -> None:
        """``module`` writes ``value`` on its output ``port`` (end of its compute phase)."""

    def wants_write(self, module: str, port: str) -> bool:
        """Whether :meth:`on_write` is to be called for ``module.port`` (default: every
        port). Asked once per port before the run: an observer that only follows some ports
        saves a call per write of the others."""
        return True

    def on_signal(self, t_ns: int, name: str, value: Any) -> None:
        """A signal occurs: an event port ``module.port`` written with a value that is neither
        ``None`` nor ``False``, or a signal posted with ``Simulation.post_signal``."""

    def on_message(self, t_ns: int, bus: str, kind: str, connection: str,
                   queued_ns: int) -> None:
        """A bus message (``data``, ``request`` or ``reply``) is delivered after waiting
        ``queued_ns`` for the bus."""

    def on_activate(self, t_ns: int, module: str) -> None:
        """``module`` starts releasing jobs."""

    def on_kill(self, t_ns: int, module: str) -> None:
        """``module`` stops; its unfinished job is aborted."""

    def on_param(self, t_ns: int, module: str, name: str, value: Any) -> None:
        """A parameter of ``module`` changes (type-1 exception)."""

    def on_deadlock(self, t_ns: int, cycle: tuple[str, ...]) -> None:
        """Blocked modules wait on each other (``cycle`` of ``module.port``); the run stops."""


class EventLog(Observer):
    """Records every callback as a tuple ``(hook, t_ns, *args)`` in :attr:`events`.

    Values other than ``int``/``str``/``bool``/``None`` are recorded by ``repr`` so the log
    compares exactly (determinism tests, traces).
    """

    def __init__(self) -> None:
        self.events: list[tuple] = []


def _plain(value: Any) -> Any:
    return value if value is None or isinstance(value, (int, str, bool)) else repr(value)


def _recorder(hook: str) -> Any:
    def record(self: EventLog, *args: Any) -> None:
        self.events.append((hook, *[_plain(arg) for arg in args]))
    record.__name__ = hook
    record.__doc__ = f"Record ``{hook}``."
    return record


for _hook in HOOKS:
    setattr(EventLog, _hook, _recorder(_hook))


def listeners(observers: list[Observer], hook: str) -> list[Any]:
    """Bound methods of ``observers`` that override ``hook``."""
    default = getattr(Observer, hook)
    found = []
    for observer in observers:
        if getattr(type(observer), hook, default) is not default:
            found.append(getattr(observer, hook))
    return found
