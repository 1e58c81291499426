"""An input script (a counterexample of ``orccad check``) run against the plant.

:func:`script_injections` turns the instants of an ``orccad react`` script into the
injections of a run (``orccad run --inject-from SCRIPT``, the console's "run against the
plant"): each instant with inputs becomes its inputs raised at that instant's simulated time.
An instant is one reaction of the automaton, so instants keep their order and are at least one
reaction *tick* apart: instant ``k`` is at its script time ``@T`` when it has one, else one tick
after the previous instant, and never earlier than one tick after it (the first instant is the
run's first reaction, at 0 s). Instants without inputs only set the pace.

Between the script's instants the run is the plant's: its observers fire and its tasks end
when the robot does, so the run may leave the counterexample where the plant disagrees with
it; the report's properties say whether the run violates the property too.
"""

from __future__ import annotations

from collections.abc import Sequence

from orccad_app.mission.injection import Injection
from orccad_app.reactive.script import Instant

__all__ = ["script_injections", "instant_times"]


def instant_times(instants: Sequence[Instant], tick_ns: int) -> list[int]:
    """The simulated time [ns] of each instant (see the module docstring)."""
    if tick_ns <= 0:
        raise ValueError(f"tick_ns must be positive, got {tick_ns}")
    times: list[int] = []
    for instant in instants:
        earliest = times[-1] + tick_ns if times else 0
        wanted = instant.time_ns if instant.time_ns is not None else earliest
        times.append(max(wanted, earliest))
    return times


def script_injections(instants: Sequence[Instant], tick_ns: int) -> list[Injection]:
    """The inputs of ``instants`` as injections at their instants' times."""
    return [Injection(name, time_ns, value)
            for instant, time_ns in zip(instants, instant_times(instants, tick_ns))
            for name, value in instant.inputs.items()]
