"""How long the 8 protocols can make a job wait: the blocking terms of the timing analysis.

The executive runs a job as *read inputs (a read may wait) → compute on the processor →
write outputs (a write may wait)*. Waiting on a read delays the moment the job competes for
its processor (release jitter ``J``); waiting on a write delays its end after the compute
phase. Every bound below is relative to the job's release ``r`` and assumes that each
Module-Task finishes every job before its next release (the analysis checks it: a job still
running at its next release is a failure).

Notation: ``P`` the producer, ``C`` the consumer; ``A_P`` the latest time after its release
at which ``P`` attempts the write (compute end plus its earlier writes' waits); ``ρ_C`` the
latest time after its release at which ``C`` reads the port (its earlier reads' waits); ``Δ``
the bus delay of a message (0 on one processor); ``gap(X→Y, x)`` the longest time from ``x``
after a release of X to the next release of Y (:mod:`orccad_app.tcs.phasing`: exact from the
gcd of the periods when both start together, else the period of Y).

**Consumer side** (read done by, ``τ`` being the reads so far):

- ``asyn/syn``: a value written by the first job of P released at or after ``r`` is fresh
  for this job, wherever it reads: ``τ = max(τ, gap(C→P, 0) + A_P + Δ)``;
- ``syn/syn``: that same job of P can only meet this job: ``τ = max(τ, gap + A_P) + Δ``;
- ``asyn/synF`` and ``asyn/synDF`` on one processor: the next write after the read; from the
  release ``gap + A_P + Δ``, later ``τ + T_P + A_P + Δ``;
- ``asyn/synD``: request and reply: ``τ + Δ_request + Δ_reply`` (0 on one processor);
- ``asyn/synDF`` across the bus: ``τ + Δ_request + T_P + A_P + Δ_reply``; from the release,
  when P's execution time is at least ``Δ_request`` (so the job of P released at or after
  ``r`` writes after the request has arrived), ``gap + A_P + Δ_reply``.

**Producer side** (the write's wait ends by):

- ``syn/asyn``: no wait when C's latest release at or before ``r`` comes after P's previous
  write and C reads there at once (``ρ_C = 0``, ``prev(P→C) < T_P - R_P``); else as
  ``synF/asyn``;
- ``synF/asyn``: the next read: ``A + gap(P→C, A) + ρ_C``, the gap to a release strictly
  after the write (a write at the instant of a release may come after that release's reads:
  a job with no execution time writes after the instant's releases);
- ``syn/syn``: when the latest release of C at or before ``r`` follows P's previous job
  (``prev(P→C) < T_P - R_P``), that job of C is P's partner: ``max(A, ρ_C) + Δ``; else
  ``A + gap(P→C, A) + ρ_C + Δ`` (strict gap).

**By construction.** A consumer that waits for every value (``syn``, ``synF``, ``synDF``,
``syn/syn``) reading faster than its producer writes (``T_C < T_P``), or a producer that waits
for every read (``syn/asyn``, ``synF/asyn``, ``syn/syn``) writing faster than its consumer reads
(``T_P < T_C``), must overrun: :func:`rate_mismatch` names it. Waiting on a sporadic partner,
or on one that starts in a later phase, has no bound.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from orccad_app.tcs.phasing import Activation, Phase, next_release_gap_ns, previous_release_gap_ns
from orccad_app.tcs.protocol import Protocol

if TYPE_CHECKING:
    from orccad_app.tcs.connection import Connection
    from orccad_app.tcs.module_task import ModuleTask

__all__ = ["CONSUMER_WAITS_EACH_VALUE", "PRODUCER_WAITS_EACH_READ", "Mismatch", "rate_mismatch",
           "read_done_ns", "WriteBound", "write_done_ns"]

CONSUMER_WAITS_EACH_VALUE = frozenset({Protocol.SYN_SYN, Protocol.ASYN_SYN, Protocol.ASYN_SYNF,
                                       Protocol.ASYN_SYNDF})
"""Protocols whose consumer needs one new write per read."""

PRODUCER_WAITS_EACH_READ = frozenset({Protocol.SYN_SYN, Protocol.SYN_ASYN, Protocol.SYNF_ASYN})
"""Protocols whose producer needs one read per write."""


@dataclass(frozen=True, slots=True)
class Mismatch:
    """A connection that makes a Module-Task overrun by construction.

    :param module: the Module-Task that waits.
    :param reason: why, naming the connection and the rates.
    """

    module: str
    reason: str


def _ms(ns: int) -> str:
    return f"{ns / 1e6:g} ms"


def rate_mismatch(connection: Connection, producer: ModuleTask, consumer: ModuleTask,
                  phases: dict[str, Phase]) -> Mismatch | None:
    """Whether ``connection`` makes a Module-Task overrun by construction, and why."""
    protocol = connection.protocol
    p, c = phases[producer.name], phases[consumer.name]
    t_p, t_c = producer.min_interarrival_ns, consumer.min_interarrival_ns
    if protocol in CONSUMER_WAITS_EACH_VALUE:
        why = _partner_problem(consumer.name, "writes", producer.name, p, c)
        if why is None and t_p > t_c:
            why = (f"'{consumer.name}' reads every {_ms(t_c)} and waits for a new value each "
                   f"time, but '{producer.name}' writes every {_ms(t_p)}: it overruns by "
                   f"construction")
        if why is not None:
            return Mismatch(consumer.name, f"{connection.label}: {why}")
    if protocol in PRODUCER_WAITS_EACH_READ:
        why = _partner_problem(producer.name, "reads", consumer.name, c, p)
        if why is None and t_p < t_c:
            why = (f"'{producer.name}' writes every {_ms(t_p)} and waits for a read each "
                   f"time, but '{consumer.name}' reads every {_ms(t_c)}: it overruns by "
                   f"construction")
        if why is not None:
            return Mismatch(producer.name, f"{connection.label}: {why}")
    return None


def _partner_problem(waiter: str, action: str, partner: str, partner_phase: Phase,
                     waiter_phase: Phase) -> str | None:
    if partner_phase.activation is Activation.SPORADIC:
        return (f"'{waiter}' waits for {action} of the sporadic '{partner}', which may never "
                f"come (no bound)")
    if partner_phase.starts_after(waiter_phase):
        return (f"'{waiter}' waits for {action} of '{partner}', which starts in a later phase "
                f"(no bound)")
    return None


def read_done_ns(tau: int, connection: Connection, producer: ModuleTask, consumer: ModuleTask,
                 phases: dict[str, Phase], attempt_ns: int, data_ns: int, request_ns: int,
                 remote: bool) -> int | None:
    """When the consumer's read of ``connection`` is done at the latest, after its release
    [ns], given its earlier reads done by ``tau``; ``None`` when unbounded.

    :param attempt_ns: ``A_P``, the producer's latest write attempt after its release.
    :param data_ns: the bus delay of a data (or reply) message, 0 on one processor.
    :param request_ns: the bus delay of a request message.
    """
    protocol = connection.protocol
    if protocol in (Protocol.ASYN_ASYN, Protocol.SYN_ASYN, Protocol.SYNF_ASYN):
        return tau
    if protocol is Protocol.ASYN_SYND:
        return tau + request_ns + data_ns if remote else tau
    gap = next_release_gap_ns(phases[consumer.name], phases[producer.name], 0)
    if gap is None:
        return None
    period = producer.min_interarrival_ns
    if protocol is Protocol.ASYN_SYN:
        return max(tau, gap + attempt_ns + data_ns)
    if protocol is Protocol.SYN_SYN:
        return max(tau, gap + attempt_ns) + data_ns
    if protocol is Protocol.ASYN_SYNDF and remote:
        earliest = producer.wcet_ns if producer.bcet_ns is None else producer.bcet_ns
        if tau == 0 and earliest >= request_ns:
            return gap + attempt_ns + data_ns
        return tau + request_ns + period + attempt_ns + data_ns
    # asyn/synF, and asyn/synDF on one processor: the next write after the read
    if tau == 0:
        return gap + attempt_ns + data_ns
    return tau + period + attempt_ns + data_ns


@dataclass(frozen=True, slots=True)
class WriteBound:
    """When a write is done at the latest, after the job's release [ns].

    :param done_ns: the bound.
    :param may_wait: whether the write can wait for a read at all (then it can end at a
        release instant of the consumer: the job must end strictly before its own next one).
    """

    done_ns: int
    may_wait: bool


def write_done_ns(attempt_ns: int, connection: Connection, producer: ModuleTask,
                  consumer: ModuleTask, phases: dict[str, Phase], response_ns: int,
                  read_at_ns: int, data_ns: int) -> WriteBound | None:
    """When the producer's write of ``connection`` is done at the latest, given the write
    attempt at ``attempt_ns``; ``None`` when unbounded.

    :param response_ns: the producer's current response bound ``R_P``.
    :param read_at_ns: ``ρ_C``, the consumer's latest read of the port after its release.
    :param data_ns: the bus delay of a data message, 0 on one processor.
    """
    protocol = connection.protocol
    if protocol not in PRODUCER_WAITS_EACH_READ:
        return WriteBound(attempt_ns, False)
    p, c = phases[producer.name], phases[consumer.name]
    previous = previous_release_gap_ns(p, c)
    slack = producer.min_interarrival_ns - response_ns
    if protocol is Protocol.SYN_ASYN and read_at_ns == 0 and previous is not None \
            and previous < slack:
        return WriteBound(attempt_ns, False)
    if protocol is Protocol.SYN_SYN and previous is not None and previous < slack:
        return WriteBound(max(attempt_ns, read_at_ns) + data_ns, True)
    gap = next_release_gap_ns(p, c, attempt_ns, strict=True)
    if gap is None:
        return None
    extra = data_ns if protocol is Protocol.SYN_SYN else 0
    return WriteBound(attempt_ns + gap + read_at_ns + extra, True)
