"""What a real controller adds to the executive's ideal timing: the exchange of the robot's
ports on a period of its own, and the release jitter of its threads
(docs/executive.md, *A real controller's delays*).

The executive's ideal exchange samples a sensor at the very instant a job reads it and applies
a torque at the very instant a job writes it. A real controller (``orccad sil --realtime``, or
the generated controller on a robot) exchanges the robot's ports with its I/O every
``exchange_ns``: a sensor read sees the value of the last exchange (up to one period old), a
torque written is applied at the next exchange (up to one period late). Its threads wake up
late by the machine's lateness: each periodic release of a Module-Task is late by a uniform
draw in ``[0, jitter_ns]``. A mission that works only with the ideal exchange (an observer
bound, a watchdog just met) then shows its failure rate in a campaign before it is tried in
real time.

Deterministic under the run's seed: the exchange's phase comes from the stream
``exchange/phase`` (a real I/O starts at an arbitrary instant of the controller's period), each
Module-Task's release delays from ``mt/<name>/jitter``.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from orccad_app.diagnostics import OrccadError
from orccad_app.executive.kernel import EventClass, Kernel

__all__ = ["ControllerDelays", "PortExchange", "jitter_draws", "MAX_DELAY_NS"]

_DELIVERY = EventClass.DELIVERY

MAX_DELAY_NS = 1_000_000_000
"""The longest exchange period or release jitter [ns] (1 s)."""


@dataclass(frozen=True)
class ControllerDelays:
    """The delays a real controller adds (see the module docstring); zero: the ideal exchange.

    :param exchange_ns: the period [ns] at which the robot's ports are exchanged with the
        plant (0: at the instant of every read and write).
    :param jitter_ns: the largest lateness [ns] of a periodic Module-Task's release (each drawn
        uniformly in ``[0, jitter_ns]``; the period's grid kept: releases do not drift).
    """

    exchange_ns: int = 0
    jitter_ns: int = 0

    def __post_init__(self) -> None:
        for name in ("exchange_ns", "jitter_ns"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, int) \
                    or not 0 <= value <= MAX_DELAY_NS:
                raise OrccadError(f"{name} must be an integer in [0, {MAX_DELAY_NS}] ns, got "
                                  f"{value!r}")

    @property
    def ideal(self) -> bool:
        """No delay: the executive's ideal exchange."""
        return self.exchange_ns == 0 and self.jitter_ns == 0


class PortExchange:
    """The robot's ports exchanged every ``period_ns`` (see the module docstring).

    Exchanges happen at ``t = 0`` and at ``phase + k · period_ns`` (``k >= 0``), the phase drawn
    in ``[0, period_ns)`` from the stream ``exchange/phase``; each one (first in its instant,
    class ``DELIVERY``) samples every watched sensor, then applies the torques written since
    the previous one (the latest per actuator; dropped when their Module-Task was killed
    meanwhile, as a plant that went idle keeps its idle behaviour).
    """

    def __init__(self, kernel: Kernel, period_ns: int) -> None:
        if period_ns <= 0:
            raise OrccadError(f"exchange period must be > 0 ns, got {period_ns}")
        self.period_ns = period_ns
        self._kernel = kernel
        self._watched: list[tuple[Any, str]] = []
        self._latest: dict[tuple[int, str], np.ndarray] = {}
        self._pending: dict[tuple[int, str], tuple[Any, Any, Any]] = {}
        self.exchanges = 0
        """Exchanges made so far."""
        phase = int(kernel.stream("exchange/phase").integers(0, period_ns))
        kernel.schedule(kernel.now, _DELIVERY, self._exchange, None)
        self._next = phase if phase > kernel.now else kernel.now + period_ns

    def watch(self, plant: Any, port: str) -> None:
        """Sample ``plant``'s sensor ``port`` at every exchange (once per plant and port)."""
        if (plant, port) not in self._watched:
            self._watched.append((plant, port))

    def sensor(self, plant: Any, port: str) -> np.ndarray:
        """``port``'s value at the last exchange (a copy: a reader may change it)."""
        value = self._latest.get((id(plant), port))
        if value is None:  # watched after the first exchange: sampled now
            value = self._latest[(id(plant), port)] = plant.sample(port)
        return value.copy()

    def actuate(self, plant: Any, port: str, value: Any, producer: Any) -> None:
        """Apply ``value`` to ``plant``'s actuator ``port`` at the next exchange, unless
        ``producer`` (its Module-Task's runtime) is killed before."""
        self._pending[(id(plant), port)] = (plant, value, producer)

    def _exchange(self, _: object) -> None:
        kernel = self._kernel
        self.exchanges += 1
        for plant, port in self._watched:
            self._latest[(id(plant), port)] = plant.sample(port)
        pending, self._pending = self._pending, {}
        for (_, port), (plant, value, producer) in pending.items():
            if producer is None or getattr(producer, "active", True):
                plant.actuate(port, value)
        when = self._next
        self._next = when + self.period_ns
        kernel.schedule(when, _DELIVERY, self._exchange, None)


def jitter_draws(kernel: Kernel, module: str, jitter_ns: int) -> Any:
    """An endless iterator of release delays [ns] of ``module``, uniform in ``[0, jitter_ns]``
    from the stream ``mt/<module>/jitter``, drawn 256 at a time."""
    stream = kernel.stream(f"mt/{module}/jitter")
    while True:
        yield from stream.integers(0, jitter_ns, endpoint=True, size=256).tolist()
