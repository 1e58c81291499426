"""Sporadic (interrupt-driven) Module-Tasks: released by events, never more often than their
minimum inter-arrival time (RR-1801 §3.4.1: an observer "may be either periodic or activated
under interruption").

A Module-Task whose :attr:`~orccad_app.tcs.module_task.ModuleTask.activation` is
``SPORADIC`` has no periodic release: its ``period_ns`` is its minimum inter-arrival time
``T_min``. An **interrupt** asks for a release:

- a write on one of its connected inputs by another Module-Task: at the write on the same
  processor, at the delivery of the data message across the bus (push protocols); an event
  port raises it only when it fires (a value that is neither ``None`` nor ``False``);
- :meth:`Simulation.interrupt <orccad_app.executive.simulation.Simulation.interrupt>`
  (an external interrupt line: a test, a sensor driver).

The release follows the interrupt in the same instant (an event of class ``RELEASE``, after
the write that caused it, so the job reads the new value), unless the previous release was
less than ``T_min`` ago: it is then **deferred** to ``previous + T_min``. Interrupts arriving
while a release is already due are **coalesced** into it (a pending-interrupt latch: one
release serves them all). Releases are therefore at least ``T_min`` apart, which is what the
schedulability analysis assumes (a periodic task of period ``T_min``). A release that finds
the previous job unfinished is skipped and counted as an overrun, as for periodic ones.
Interrupts while the Module-Task is inactive are ignored. Re-activation starts afresh (no
minimum to wait).

Across the bus the interrupt is the data message itself, so pull protocols (``asyn/synD``,
``asyn/synDF``: nothing is sent on a write) and those whose value crosses only when the
consumer reads (``syn/syn``, ``syn/asyn``, ``synF/asyn``) do not interrupt a sporadic consumer
on another processor (its other inputs or external interrupts must release it; a Robot-Task
whose sporadic module has no input that can interrupt it is refused when compiled).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from orccad_app.executive.kernel import EventClass, Kernel
from orccad_app.executive.observer import Observer
from orccad_app.tcs.module_task import Activation, ModuleTask
from orccad_app.tcs.protocol import Protocol

if TYPE_CHECKING:
    from orccad_app.executive.task_runtime import ModuleTaskRuntime
    from orccad_app.tcs.graph import TCS

__all__ = ["SporadicStats", "SporadicRelease", "SporadicReleases", "sporadic_releases",
           "PUSHED_ON_WRITE"]

_RELEASE = EventClass.RELEASE
PUSHED_ON_WRITE = {Protocol.ASYN_ASYN, Protocol.ASYN_SYN, Protocol.ASYN_SYNF}
"""Protocols that send a data message at each write (the message is the interrupt)."""


@dataclass(slots=True)
class SporadicStats:
    """Counters of one sporadic Module-Task.

    :param min_interarrival_ns: its minimum inter-arrival time [ns].
    :param interrupts: interrupts received while active.
    :param released: releases made.
    :param deferred: interrupts that came less than the minimum after the previous release
        (their release was postponed to the end of the minimum).
    :param coalesced: interrupts served by a release already due.
    :param min_gap_ns: the shortest time between two releases [ns] (-1 before the second).
    """

    min_interarrival_ns: int
    interrupts: int = 0
    released: int = 0
    deferred: int = 0
    coalesced: int = 0
    min_gap_ns: int = -1


class SporadicRelease:
    """The release logic of one sporadic Module-Task."""

    def __init__(self, kernel: Kernel, runtime: ModuleTaskRuntime) -> None:
        self.runtime = runtime
        self.stats = SporadicStats(runtime.task.min_interarrival_ns)
        self._kernel = kernel
        self._last_ns: int | None = None
        self._due: list[Any] | None = None

    def interrupt(self) -> None:
        """An interrupt now: release now, or at the end of the minimum, or join the due one."""
        if not self.runtime.active:
            return
        stats = self.stats
        stats.interrupts += 1
        now = self._kernel.now
        earliest = now if self._last_ns is None else self._last_ns + stats.min_interarrival_ns
        if self._due is not None:
            stats.coalesced += 1
            return
        if earliest > now:
            stats.deferred += 1
        self._due = self._kernel.schedule(max(now, earliest), _RELEASE, self._fire)

    def _fire(self, _: object) -> None:
        self._due = None
        if not self.runtime.active:
            return
        now = self._kernel.now
        stats = self.stats
        if self._last_ns is not None:
            gap = now - self._last_ns
            if stats.min_gap_ns < 0 or gap < stats.min_gap_ns:
                stats.min_gap_ns = gap
        self._last_ns = now
        stats.released += 1
        self.runtime.release_job(now)

    def restart(self) -> None:
        """Forget the previous release and any due one (activation, kill)."""
        self._kernel.cancel(self._due)
        self._due = None
        self._last_ns = None


class SporadicReleases(Observer):
    """Turns writes and bus deliveries into interrupts of the sporadic Module-Tasks they feed.

    :param local: ``(producer module, port)`` -> sporadic consumers on its processor.
    :param remote: connection label -> the sporadic consumer its data messages interrupt.
    """

    def __init__(self, releases: dict[str, SporadicRelease],
                 local: dict[tuple[str, str], list[SporadicRelease]],
                 remote: dict[str, SporadicRelease]) -> None:
        self.releases = releases
        self._local = local
        self._remote = remote

    def on_write(self, t_ns: int, module: str, port: str, value: Any) -> None:
        """A Module-Task writes a port: interrupt the sporadic consumers beside it."""
        for release in self._local.get((module, port), ()):
            release.interrupt()

    def on_message(self, t_ns: int, bus: str, kind: str, connection: str,
                   queued_ns: int) -> None:
        """A data message is delivered: interrupt the sporadic consumer it feeds."""
        release = self._remote.get(connection)
        if release is not None and kind == "data":
            release.interrupt()

    def on_activate(self, t_ns: int, module: str) -> None:
        """A sporadic Module-Task starts afresh."""
        release = self.releases.get(module)
        if release is not None:
            release.restart()

    def on_kill(self, t_ns: int, module: str) -> None:
        """A killed sporadic Module-Task's due release is withdrawn."""
        release = self.releases.get(module)
        if release is not None:
            release.restart()


def sporadic_releases(tcs: TCS, kernel: Kernel,
                      runtimes: dict[str, ModuleTaskRuntime]) -> SporadicReleases | None:
    """The interrupt wiring of ``tcs``'s sporadic Module-Tasks, ``None`` when it has none."""
    releases = {name: SporadicRelease(kernel, runtime) for name, runtime in runtimes.items()
                if runtime.task.activation is Activation.SPORADIC}
    if not releases:
        return None
    local: dict[tuple[str, str], list[SporadicRelease]] = {}
    remote: dict[str, SporadicRelease] = {}
    for connection in tcs.connections:
        release = releases.get(connection.consumer_module)
        producer = tcs.module(connection.producer_module)
        if release is None or not isinstance(producer, ModuleTask):
            continue
        if producer.processor == release.runtime.task.processor:
            local.setdefault((producer.name, connection.producer_port), []).append(release)
        elif connection.protocol in PUSHED_ON_WRITE:
            remote[connection.label] = release
    return SporadicReleases(releases, local, remote)
