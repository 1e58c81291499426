"""The campaign spec: a TOML file declaring what varies from run to run (docs/campaigns.md).

::

    mission = "AuvSurvey"           # optional: the file's only mission by default
    runs = 200                      # default number of runs (--runs overrides)
    seed = 1                        # the campaign's seed: every run's setting is drawn from it
    until_s = 400                   # simulated-time limit of each run [s]
    seeds = "UI(0, 1000000)"        # the runs' seeds (default: UI(0, 2**31 - 1))
    signals = ["auv.depth"]         # sensor ports whose extrema each run records

    [params]                        # robot type parameters and sensor noise (--set)
    "auv.cb_height_m" = "U(0.03, 0.07)"
    "auv.depth.noise_std" = "U(0.01, 0.05)"

    [timing]                        # Module-Task period / WCET / BCET [ms] (--timing)
    "Survey.pilot.wcet_ms" = "U(0.5, 5)"

    [controller]                    # a real controller's delays [µs] (--exchange-us,
    exchange_us = "U(0, 1000)"      # --jitter-us: docs/executive.md)
    jitter_us = "U(0, 200)"

    [[inject]]                      # an input or a plant fault at a random time (--inject)
    event = "auv.leak=1@U(20, 170)"
    probability = 0.3               # Bernoulli occurrence (default 1)

    [[check]]                       # a bound on a run metric: verdict and robustness
    name = "shallow"
    metric = "max(auv.depth)"
    below = 30.0

:func:`load_spec` reads and checks the file's form; an error names ``FILE:LINE:COL`` of the
offending key and exits 2. Names are checked against the mission later
(:func:`orccad_app.campaign.adapter.check_spec`).
"""

from __future__ import annotations

import math
import re
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from orccad_app.campaign.distributions import (Distribution, DistributionError, Kind,
                                               parse_distribution)
from orccad_app.diagnostics import OrccadError, SourceLocation, cut
from orccad_app.mission.injection import PlantFault

__all__ = ["CampaignSpec", "ParamEntry", "TimingEntry", "ControllerEntry", "InjectEntry",
           "Check", "load_spec", "CONTROLLER_KEYS",
           "parse_spec", "SpecLocator", "DEFAULT_SEEDS", "MAX_RUNS", "MAX_UNTIL_S", "MAX_SEED"]

DEFAULT_SEEDS = parse_distribution(f"UI(0, {2 ** 31 - 1})")
_TOP = ("mission", "runs", "seed", "until_s", "seeds", "signals", "params", "timing",
        "controller", "inject", "check")
CONTROLLER_KEYS = ("exchange_us", "jitter_us")
"""The keys of ``[controller]``: ``orccad run``'s ``--exchange-us`` and ``--jitter-us``."""
MAX_DELAY_US = 1e6
"""The largest exchange period or release jitter a spec may draw [µs] (1 s)."""
_EVENT = re.compile(r"^\s*([A-Za-z_][\w.]*)\s*(?:=(.*?)|\((.*)\))?\s*@(.+)$", re.S)
_DRAWS = "U(a, b), UI(a, b), N(mu, sigma), N(mu, sigma, lo, hi), choice(v, ...) or B(p)"
_METRIC = re.compile(r"^(?:(max|min)\(([A-Za-z_][\w.]*(?:\[\d+\])?)\)|sim_time_s|"
                     r"completion_time_s|deadline_misses|"
                     r"([A-Za-z_]\w*)\.tracking_error\.(max|rms))$")


MAX_RUNS = 1_000_000
"""Most runs a campaign may ask for (``runs``, ``--runs``, the Chernoff–Hoeffding bound of
``--epsilon``): checked before the first run, the list of runs is never built past it."""

MAX_UNTIL_S = 365 * 24 * 3600.0
"""Longest horizon of a run [s]: one year, as ``orccad run --until`` and durations."""

MAX_SEED = 2**63 - 1
"""Largest seed (``seed``, ``seeds``): every run's replay command is an ``orccad run --seed``,
which takes 64-bit seeds."""


@dataclass(frozen=True)
class ParamEntry:
    """``"ROBOT.PARAM" = DIST`` or ``"ROBOT.PORT.noise_std" = DIST`` of ``[params]``."""

    target: str
    dist: Distribution
    key: tuple


@dataclass(frozen=True)
class TimingEntry:
    """``"TASK.MODULE.FIELD" = DIST`` of ``[timing]`` [ms]."""

    target: str
    dist: Distribution
    key: tuple


@dataclass(frozen=True)
class ControllerEntry:
    """``exchange_us = DIST`` or ``jitter_us = DIST`` of ``[controller]`` [µs]: the delays a
    real controller adds (:mod:`orccad_app.executive.delays`)."""

    target: str
    dist: Distribution
    key: tuple


@dataclass(frozen=True)
class InjectEntry:
    """One ``[[inject]]``: ``name`` raised (or the fault set to ``value``) at ``time`` [s].

    :param fault: the plant fault ``name`` sets, ``None`` for an automaton input.
    """

    name: str
    fault: PlantFault | None
    value: Distribution | None
    time: Distribution
    probability: float
    key: tuple


@dataclass(frozen=True)
class Check:
    """One ``[[check]]``: ``metric < below`` and/or ``metric > above``; robustness is the
    margin in the metric's unit (negative: violated)."""

    name: str
    metric: str
    below: float | None
    above: float | None
    key: tuple


@dataclass(frozen=True)
class CampaignSpec:
    """A checked spec (see the module docstring)."""

    path: str
    text: str
    mission: str | None = None
    runs: int = 100
    seed: int = 0
    until_s: float | None = None
    seeds: Distribution = DEFAULT_SEEDS
    signals: tuple[str, ...] = ()
    params: tuple[ParamEntry, ...] = ()
    timings: tuple[TimingEntry, ...] = ()
    controller: tuple[ControllerEntry, ...] = ()
    injections: tuple[InjectEntry, ...] = ()
    checks: tuple[Check, ...] = ()
    locator: SpecLocator | None = field(default=None, compare=False)

    def error(self, message: str, key: tuple = ()) -> OrccadError:
        """An error located at ``key`` (a path of TOML keys) in the spec file."""
        location = self.locator.locate(key) if self.locator is not None else None
        return OrccadError(message, location)


class SpecLocator:
    """Finds the line of a TOML key path (``("inject", 1, "event")``) by scanning the text."""

    _HEADER = re.compile(r"^\s*(\[\[?)\s*([\w.\"-]+)\s*\]\]?")
    _KEY = re.compile(r"^\s*(\"[^\"]*\"|'[^']*'|[\w.-]+)\s*=")

    def __init__(self, path: str, text: str) -> None:
        self.path = path
        self.keys: dict[tuple, tuple[int, int]] = {}
        table: tuple = ()
        counts: dict[str, int] = {}
        for number, line in enumerate(text.splitlines(), start=1):
            header = self._HEADER.match(line)
            if header:
                name = header.group(2).strip("\"'")
                if header.group(1) == "[[":
                    counts[name] = counts.get(name, -1) + 1
                    table = (name, counts[name])
                else:
                    table = (name,)
                self.keys.setdefault(table, (number, line.index(name) + 1))
                continue
            key = self._KEY.match(line)
            if key:
                name = key.group(1).strip("\"'")
                self.keys.setdefault((*table, name), (number, line.index(key.group(1)) + 1))

    def locate(self, key: tuple) -> SourceLocation:
        """The location of ``key`` or of its closest enclosing table."""
        while key and key not in self.keys:
            key = key[:-1]
        line, col = self.keys.get(key, (1, 1))
        return SourceLocation(self.path, line, col)


def load_spec(path: str | Path) -> CampaignSpec:
    """Read and check the spec file ``path``; raise a located :class:`OrccadError`."""
    from orccad_app.pipeline import read_source

    path = str(path)
    # a regular file of at most MAX_SOURCE_BYTES, UTF-8 (a located error at the first
    # undecodable byte): never a FIFO that blocks or /dev/zero read until memory runs out
    return parse_spec(read_source(path), path)


def parse_spec(text: str, path: str = "<spec>") -> CampaignSpec:
    """Parse the TOML ``text`` of a spec (see :func:`load_spec`)."""
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as error:
        found = re.search(r"\(at line (\d+), column (\d+)\)", str(error))
        message = re.sub(r"\s*\(at (line \d+, column \d+|end of document)\)", "", str(error))
        if found:
            where = SourceLocation(path, int(found.group(1)), int(found.group(2)))
        else:  # "(at end of document)"
            where = SourceLocation(path, max(1, len(text.splitlines())), 1)
        raise OrccadError(f"bad TOML: {message}", where) from None
    spec = CampaignSpec(path, text, locator=SpecLocator(path, text))
    return _Reader(spec, data).read()


class _Reader:
    def __init__(self, spec: CampaignSpec, data: dict[str, Any]) -> None:
        self.spec = spec
        self.data = data

    def fail(self, message: str, *key: Any) -> OrccadError:
        return self.spec.error(message, key)

    def read(self) -> CampaignSpec:
        data = self.data
        for key in data:
            if key not in _TOP:
                raise self.fail(f"unknown key '{key}' (keys: {', '.join(_TOP)})", key)
        values: dict[str, Any] = {}
        if "mission" in data:
            values["mission"] = self.string(data["mission"], "mission")
        if "runs" in data:
            values["runs"] = self.integer(data["runs"], 1, "runs", maximum=MAX_RUNS)
        if "seed" in data:
            values["seed"] = self.integer(data["seed"], 0, "seed", maximum=MAX_SEED)
        if "until_s" in data:
            until = data["until_s"]
            # NaN and infinities fail the range test too
            if isinstance(until, bool) or not isinstance(until, (int, float)) \
                    or not 0 < until <= MAX_UNTIL_S:
                raise self.fail(f"until_s must be a number of seconds in (0, {MAX_UNTIL_S:g}] "
                                f"(one year), got {cut(repr(until))}", "until_s")
            values["until_s"] = float(until)
        if "seeds" in data:
            seeds = self.dist(data["seeds"], "seeds")
            if not seeds.integral or seeds.bounds[0] < 0 or seeds.bounds[1] > MAX_SEED:
                raise self.fail(f"seeds must draw integers in [0, {MAX_SEED}] (UI(a, b) or "
                                "choice of integers)", "seeds")
            values["seeds"] = seeds
        values["signals"] = self.signals(data.get("signals", []))
        values["params"] = tuple(ParamEntry(k, self.dist(v, "params", k), ("params", k))
                                 for k, v in self.table("params").items())
        values["timings"] = tuple(TimingEntry(k, self.dist(v, "timing", k), ("timing", k))
                                  for k, v in self.table("timing").items())
        values["controller"] = tuple(self.controller(k, v)
                                     for k, v in self.table("controller").items())
        values["injections"] = tuple(self.inject(i, item)
                                     for i, item in enumerate(self.array("inject")))
        values["checks"] = tuple(self.check(i, item)
                                 for i, item in enumerate(self.array("check")))
        names = [c.name for c in values["checks"]]
        for index, name in enumerate(names):
            if names.index(name) != index:
                raise self.fail(f"two checks are named '{name}'", "check", index, "name")
        return CampaignSpec(**{**self.spec.__dict__, **values})

    def string(self, value: Any, *key: Any) -> str:
        if not isinstance(value, str) or not value.strip():
            raise self.fail(f"{key[-1]} must be a non-empty string, got {cut(repr(value))}", *key)
        return value.strip()

    def integer(self, value: Any, minimum: int, *key: Any, maximum: int = 2**63 - 1) -> int:
        if isinstance(value, bool) or not isinstance(value, int) or not \
                minimum <= value <= maximum:
            raise self.fail(f"{key[-1]} must be an integer in [{minimum}, {maximum}], got "
                            f"{cut(repr(value))}", *key)
        return value

    def dist(self, value: Any, *key: Any) -> Distribution:
        try:
            return parse_distribution(value)
        except DistributionError as error:
            raise self.fail(str(error), *key) from None

    def table(self, name: str) -> dict[str, Any]:
        value = self.data.get(name, {})
        if not isinstance(value, dict):
            raise self.fail(f"'{name}' must be a table ([{name}])", name)
        return value

    def array(self, name: str) -> list[dict[str, Any]]:
        value = self.data.get(name, [])
        if not isinstance(value, list) or not all(isinstance(v, dict) for v in value):
            raise self.fail(f"'{name}' must be an array of tables ([[{name}]])", name)
        return value

    def signals(self, value: Any) -> tuple[str, ...]:
        if not isinstance(value, list) or not all(isinstance(v, str) for v in value):
            raise self.fail("signals must be a list of ROBOT.PORT strings", "signals")
        for signal in value:
            if not re.fullmatch(r"[A-Za-z_]\w*\.[A-Za-z_]\w*(\[\d+\])?", signal):
                raise self.fail(f"signal {cut(repr(signal))}: expected ROBOT.PORT or ROBOT.PORT[i]",
                                "signals")
        return tuple(value)

    def controller(self, name: str, value: Any) -> ControllerEntry:
        key = ("controller", name)
        if name not in CONTROLLER_KEYS:
            raise self.fail(f"unknown key '{name}' in [controller] (keys: "
                            f"{', '.join(CONTROLLER_KEYS)})", *key)
        dist = self.dist(value, *key)
        low, high = dist.bounds
        if not 0 <= low <= high <= MAX_DELAY_US:
            raise self.fail(f"{name} must draw microseconds in [0, {MAX_DELAY_US:g}], got "
                            f"{value!r}", *key)
        return ControllerEntry(name, dist, key)

    def inject(self, index: int, item: dict[str, Any]) -> InjectEntry:
        key = ("inject", index)
        for name in item:
            if name not in ("event", "probability"):
                raise self.fail(f"unknown key '{name}' in [[inject]] (keys: event, "
                                f"probability)", *key, name)
        if "event" not in item:
            raise self.fail("[[inject]] needs an event (e.g. event = \"auv.leak=1@U(20, 170)\")",
                            *key)
        text = self.string(item["event"], *key, "event")
        match = _EVENT.match(text)
        if match is None:
            raise self.fail(f"bad event {cut(repr(text))}: expected SIGNAL@TIME, "
                            f"SIGNAL(VALUE)@TIME or ROBOT.FAULT=VALUE@TIME (TIME and VALUE "
                            f"numbers or distributions)", *key, "event")
        name, fault_value, signal_value, when = match.groups()
        fault = None if fault_value is None else PlantFault.named(name)
        if fault_value is not None and fault is None:
            raise self.fail(f"bad event {cut(repr(text))}: a plant fault is "
                            "ROBOT.FAULT=VALUE@TIME",
                            *key, "event")
        raw = signal_value if fault is None else fault_value
        value = None
        if raw is not None:
            raw = raw.strip()
            if raw.startswith("["):
                raise self.fail(f"event {cut(repr(text))}: a campaign draws numbers, not "
                                f"vectors: VALUE is a number or a distribution ({_DRAWS}); "
                                f"inject a vector input with orccad run --inject "
                                f"'{name}([x, y, ...])@T'", *key, "event")
            value = self.dist(raw[:-1] if raw.endswith("%") else raw, *key, "event")
        time = self.dist(when.strip().removesuffix("s") if when.strip().endswith(")s")
                         else when.strip(), *key, "event")
        if time.bounds[0] < 0:
            raise self.fail(f"event {cut(repr(text))}: times must be >= 0 s", *key, "event")
        probability = item.get("probability", 1.0)
        if (isinstance(probability, bool) or not isinstance(probability, (int, float))
                or not 0 <= probability <= 1):
            raise self.fail(f"probability must be a number in [0, 1], got {cut(repr(probability))}",
                            *key, "probability")
        return InjectEntry(name, fault, value, time, float(probability), key)

    def check(self, index: int, item: dict[str, Any]) -> Check:
        key = ("check", index)
        for name in item:
            if name not in ("name", "metric", "below", "above"):
                raise self.fail(f"unknown key '{name}' in [[check]] (keys: name, metric, "
                                f"below, above)", *key, name)
        name = self.string(item.get("name"), *key, "name")
        if not re.fullmatch(r"[A-Za-z_]\w*", name):
            raise self.fail(f"check name {cut(repr(name))} must be an identifier", *key, "name")
        metric = self.string(item.get("metric"), *key, "metric")
        if not _METRIC.match(metric):
            raise self.fail(f"unknown metric {cut(repr(metric))}: expected max(ROBOT.PORT), "
                            f"min(ROBOT.PORT), sim_time_s, completion_time_s, deadline_misses "
                            f"or TASK.tracking_error.max|rms", *key, "metric")
        bounds = {}
        for side in ("below", "above"):
            value = item.get(side)
            if value is not None and (isinstance(value, bool)
                                      or not isinstance(value, (int, float))
                                      or not math.isfinite(value)):
                raise self.fail(f"{side} must be a finite number, got {cut(repr(value))}",
                                *key, side)
            bounds[side] = None if value is None else float(value)
        if bounds["below"] is None and bounds["above"] is None:
            raise self.fail("a check needs 'below' and/or 'above'", *key)
        return Check(name, metric, bounds["below"], bounds["above"], key)


def metric_signal(metric: str) -> str | None:
    """The signal ``ROBOT.PORT[i]`` a ``max(…)``/``min(…)`` metric reads, else ``None``."""
    match = _METRIC.match(metric)
    return match.group(2) if match and match.group(2) else None


def is_constant(dist: Distribution) -> bool:
    """The distribution always gives the same value."""
    return dist.kind is Kind.CONSTANT
