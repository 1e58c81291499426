"""One run's setting: seed, horizon, injections and overrides, drawn from the spec.

A :class:`RunSetting` holds the ``orccad run`` arguments as text (``--inject``, ``--set``,
``--timing``): the campaign runs exactly what its replay command says, parsed by the same
functions, so ``orccad run FILE`` + :meth:`RunSetting.run_args` replays the run bit for bit.

Run ``i`` draws its setting from ``numpy.random.default_rng([campaign seed, i])``: it depends
only on the spec and ``i``, never on which worker runs it or in which order, so a resumed or
distributed campaign draws the same settings. Draw order: the run's seed, ``[params]`` then
``[timing]`` then ``[controller]`` in file order, then per ``[[inject]]`` its occurrence, value
and time (drawn even when it does not occur, so that one entry's probability does not shift the
others' draws).
"""

from __future__ import annotations

import shlex
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from orccad_app.campaign.distributions import round_sig
from orccad_app.campaign.spec import CampaignSpec, InjectEntry

__all__ = ["RunSetting", "draw_setting", "draw_values", "build_setting", "replay_command",
           "whole_ns_ms", "whole_ns_us", "injection_text"]


@dataclass(frozen=True)
class RunSetting:
    """The replayable setting of run ``index`` (see the module docstring).

    :param exchange_us: the robot's ports' exchange period [µs] (``--exchange-us``; 0: ideal).
    :param jitter_us: the releases' largest lateness [µs] (``--jitter-us``; 0: none).
    :param values: every drawn quantity by name (``auv.cb_height_m``,
        ``Survey.pilot.wcet_ms``, ``controller.exchange_us``, ``inject[0].occurs``,
        ``inject[0].time_s``, ``inject[0].value``): the coordinates of the run in the spec's
        space.
    """

    index: int
    seed: int
    until_s: float
    injections: tuple[str, ...] = ()
    sets: tuple[str, ...] = ()
    timings: tuple[str, ...] = ()
    values: dict[str, float] = field(default_factory=dict, compare=False)
    exchange_us: float = 0.0
    jitter_us: float = 0.0

    def run_args(self) -> list[str]:
        """The ``orccad run`` options that give this setting."""
        args = ["--seed", str(self.seed), "--until", repr(self.until_s)]
        for text in self.injections:
            args += ["--inject", text]
        for text in self.sets:
            args += ["--set", text]
        for text in self.timings:
            args += ["--timing", text]
        if self.exchange_us:
            args += ["--exchange-us", repr(self.exchange_us)]
        if self.jitter_us:
            args += ["--jitter-us", repr(self.jitter_us)]
        return args

    def options(self, **more: Any) -> Any:
        """This setting as the :class:`~orccad_app.session.RunOptions` of ``orccad run FILE
        --mission M`` with :meth:`run_args` (the default processors and bus, no pacing);
        ``more``: other options (observers, a trace...)."""
        from orccad_app.executive.delays import ControllerDelays
        from orccad_app.mission.injection import parse_injection
        from orccad_app.mission.overrides import PlanOverrides
        from orccad_app.session import RunOptions

        return RunOptions(
            overrides=PlanOverrides.from_arguments(list(self.sets), list(self.timings)),
            injections=tuple(parse_injection(text) for text in self.injections),
            seed=self.seed, until_s=self.until_s,
            delays=ControllerDelays(round(self.exchange_us * 1000),
                                    round(self.jitter_us * 1000)), **more)

    def as_dict(self) -> dict[str, Any]:
        return {"index": self.index, "seed": self.seed, "until_s": self.until_s,
                "injections": list(self.injections), "sets": list(self.sets),
                "timings": list(self.timings), "exchange_us": self.exchange_us,
                "jitter_us": self.jitter_us, "values": self.values}

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> RunSetting:
        return cls(int(data["index"]), int(data["seed"]), float(data["until_s"]),
                   tuple(data["injections"]), tuple(data["sets"]), tuple(data["timings"]),
                   dict(data.get("values", {})), float(data.get("exchange_us", 0.0)),
                   float(data.get("jitter_us", 0.0)))


def whole_ns_ms(value_ms: Any) -> float:
    """``value_ms`` [ms] rounded to a whole number of nanoseconds (its shortest text reads back
    as exactly that many nanoseconds)."""
    return round(float(value_ms) * 1e6) / 1e6


def whole_ns_us(value_us: Any) -> float:
    """``value_us`` [µs] rounded to a whole number of nanoseconds."""
    return round(float(value_us) * 1e3) / 1e3


def replay_command(file: str, mission: str, setting: RunSetting) -> str:
    """The shell command that replays ``setting``."""
    return shlex.join(["orccad", "run", file, "--mission", mission, *setting.run_args()])


def _text(value: Any) -> str:
    return repr(value) if isinstance(value, float) else str(value)


def injection_text(entry: InjectEntry, value: Any, time_s: float) -> str:
    """The ``--inject`` argument of ``entry`` with ``value`` at ``time_s``."""
    at = f"@{_text(time_s)}"
    if entry.fault is not None:
        return f"{entry.fault}={_text(value)}{at}"
    if value is not None:
        return f"{entry.name}({_text(value)}){at}"
    return f"{entry.name}{at}"


def draw_values(spec: CampaignSpec, rng: np.random.Generator) -> dict[str, Any]:
    """Every quantity of one run drawn from the spec (see the module docstring)."""
    values: dict[str, Any] = {}
    for entry in spec.params:
        values[entry.target] = entry.dist.sample(rng)
    for timing in spec.timings:  # whole nanoseconds: --timing refuses anything finer
        values[timing.target] = whole_ns_ms(timing.dist.sample(rng))
    for axis in spec.controller:  # whole nanoseconds, as --exchange-us takes them
        values[f"controller.{axis.target}"] = whole_ns_us(axis.dist.sample(rng))
    for number, inject in enumerate(spec.injections):
        values[f"inject[{number}].occurs"] = int(rng.random() < inject.probability)
        if inject.value is not None:
            values[f"inject[{number}].value"] = inject.value.sample(rng)
        values[f"inject[{number}].time_s"] = float(round_sig(float(inject.time.sample(rng)), 7))
    return values


def build_setting(spec: CampaignSpec, index: int, seed: int, until_s: float,
                  values: dict[str, Any]) -> RunSetting:
    """The setting giving ``values`` (as :func:`draw_values` names them) to the spec's
    entries; an injection that does not occur is left out (its time and value too)."""
    sets = tuple(f"{e.target}={_text(values[e.target])}" for e in spec.params)
    timings = tuple(f"{e.target}={_text(values[e.target])}" for e in spec.timings)
    injections = []
    kept = {target: float(values[target])
            for target in (*(e.target for e in spec.params), *(e.target for e in spec.timings))}
    delays = {axis.target: float(values[f"controller.{axis.target}"])
              for axis in spec.controller}
    kept.update({f"controller.{name}": value for name, value in delays.items()})
    for number, inject in enumerate(spec.injections):
        prefix = f"inject[{number}]"
        occurs = bool(values[f"{prefix}.occurs"])
        kept[f"{prefix}.occurs"] = float(occurs)
        if not occurs:
            continue
        value = values.get(f"{prefix}.value")
        time_s = values[f"{prefix}.time_s"]
        kept[f"{prefix}.time_s"] = float(time_s)
        if value is not None:
            kept[f"{prefix}.value"] = float(value)
        injections.append(injection_text(inject, value, time_s))
    return RunSetting(index, seed, until_s, tuple(injections), sets, timings, kept,
                      delays.get("exchange_us", 0.0), delays.get("jitter_us", 0.0))


def draw_setting(spec: CampaignSpec, index: int, until_s: float) -> RunSetting:
    """The setting of run ``index`` (see the module docstring)."""
    rng = np.random.default_rng([spec.seed, index])
    seed = int(spec.seeds.sample(rng))
    return build_setting(spec, index, seed, until_s, draw_values(spec, rng))
