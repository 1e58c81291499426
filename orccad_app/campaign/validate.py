"""A spec checked against its mission before any run: every name and every bound.

Each ``[params]`` and ``[timing]`` entry is planned at both ends of its distribution's support
(a parameter's declared range, a BCET above the WCET… are refused here, not at run 137);
each ``[[inject]]`` is scheduled at both ends of its time and value supports; signals and
check metrics must name what the mission has. An error points at the spec's line.
"""

from __future__ import annotations

import math
from typing import Any

from orccad_app.campaign.adapter import CompiledMission
from orccad_app.campaign.metrics import SignalExtrema
from orccad_app.campaign.distributions import round_sig
from orccad_app.campaign.setting import RunSetting, injection_text, whole_ns_ms
from orccad_app.campaign.spec import CampaignSpec, metric_signal
from orccad_app.diagnostics import OrccadError

__all__ = ["check_spec"]


def _located(spec: CampaignSpec, key: tuple, action: Any) -> Any:
    try:
        return action()
    except OrccadError as error:
        if error.location is not None and error.location.file == spec.path:
            raise
        raise spec.error(error.message, key) from None


def _ends(dist: Any) -> list[Any]:
    choices = dist.choices
    if choices is not None:
        return list(choices)
    low, high = dist.bounds
    if dist.integral:
        return [int(low), int(high)]
    return [float(low), float(high)]


def _period_probes(dist: Any) -> list[float]:
    """Periods [ms] a continuous distribution draws beside its ends: one drawing step (6
    significant digits, whole nanoseconds) inside each end, and the next ones. Two
    periods' greatest common divisor is the timers' instant period: a draw beside a round
    end (1.00001 ms beside 1 ms) makes it thousands of times finer than every period, which
    every run would pay (refused by the plan), though both ends pass."""
    if dist.choices is not None:
        return []
    low, high = (float(v) for v in dist.bounds)
    probes = []
    for end, sign in ((low, 1.0), (high, -1.0)):
        if end <= 0:
            continue
        step = max(10.0 ** (math.floor(math.log10(end)) - 5), 1e-6)  # ms: 6 digits, >= 1 ns
        for k in (1, 3, 7):
            value = whole_ns_ms(round_sig(end + sign * k * step))
            if low < value < high:
                probes.append(value)
    return probes


def check_spec(compiled: CompiledMission, spec: CampaignSpec, until_s: float) -> None:
    """Refuse, located in the spec, anything a run of it could not do."""
    if spec.mission is not None and spec.mission != compiled.name:
        raise spec.error(f"the spec is for mission '{spec.mission}', not '{compiled.name}'",
                         ("mission",))
    _located(spec, (), lambda: compiled.plan(RunSetting(0, 0, until_s)))
    for entry in spec.params:
        for value in _ends(entry.dist):
            setting = RunSetting(0, 0, until_s, sets=(f"{entry.target}={value!r}",))
            _located(spec, entry.key, lambda s=setting: compiled.plan(s))
    timings = [(t, _ends(t.dist)) for t in spec.timings]
    for timing, ends in timings:
        for value in ends:
            setting = RunSetting(0, 0, until_s, timings=(f"{timing.target}={value!r}",))
            _located(spec, timing.key, lambda s=setting: compiled.plan(s))
        probes = _period_probes(timing.dist) if timing.target.endswith(".period_ms") else []
        for value in probes:
            setting = RunSetting(0, 0, until_s, timings=(f"{timing.target}={value!r}",))
            try:
                compiled.plan(setting)
            except OrccadError as error:
                raise spec.error(f"{timing.target} = {timing.dist.text} draws periods such as "
                                 f"{value!r} ms: {error.message}; draw a period with "
                                 f"choice(...)", timing.key) from None
    for low_high in (0, -1):  # every timing at its low, then high end, together
        together = tuple(f"{t.target}={ends[low_high]!r}" for t, ends in timings)
        if together:
            _located(spec, timings[0][0].key,
                     lambda s=RunSetting(0, 0, until_s, timings=together): compiled.plan(s))
    for inject in spec.injections:
        _check_injection(compiled, spec, inject, until_s)
    _check_signals(compiled, spec, until_s)


def _check_injection(compiled: CompiledMission, spec: CampaignSpec, entry: Any,
                     until_s: float) -> None:
    declared = {signal.name: signal for signal in compiled.composition.automaton.inputs}
    signal = declared.get(entry.name)
    if not entry.fault and signal is not None and signal.type == "vector":
        raise spec.error(f"event {entry.name}: {entry.name} carries a vector, and a campaign "
                         f"draws numbers only (a number, U, UI, N, choice or B); inject it "
                         f"with orccad run --inject '{entry.name}([x, y, ...])@T'",
                         (*entry.key, "event"))
    low, high = entry.time.bounds
    if high >= until_s:
        raise spec.error(f"event at up to {high:g} s: not before the horizon until_s = "
                         f"{until_s:g} s", (*entry.key, "event"))
    values = [None] if entry.value is None else _ends(entry.value)
    for value in values:
        for time_s in (low, high):
            text = injection_text(entry, value, float(time_s))
            setting = RunSetting(0, 0, until_s, injections=(text,))
            _located(spec, (*entry.key, "event"),
                     lambda s=setting: compiled.session(s))


def _check_signals(compiled: CompiledMission, spec: CampaignSpec, until_s: float) -> None:
    extrema = SignalExtrema(spec.signals)
    session = compiled.session(RunSetting(0, 0, until_s))
    _located(spec, ("signals",), lambda: extrema.bind(session.run))
    tasks = {site.task for site in session.plan.sites}
    taken = set(compiled.property_names())
    for check in spec.checks:
        signal = metric_signal(check.metric)
        if signal is not None and signal not in spec.signals:
            raise spec.error(f"check '{check.name}': metric {check.metric} needs {signal} "
                             f"in signals", (*check.key, "metric"))
        if ".tracking_error." in check.metric and check.metric.split(".")[0] not in tasks:
            raise spec.error(f"check '{check.name}': the mission runs no Robot-Task "
                             f"'{check.metric.split('.')[0]}'", (*check.key, "metric"))
        if check.name in taken:
            raise spec.error(f"check '{check.name}': the mission has a property of that name",
                             (*check.key, "name"))
