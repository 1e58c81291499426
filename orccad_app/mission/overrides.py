"""Run-time overrides of a mission's plan: robot parameters, sensor noise, Module-Task timing.

``orccad run`` and campaigns change a planned mission without editing its source:

- ``--set ROBOT.PARAM=VALUE`` (:class:`ParamOverride`): a parameter the robot *type* declares
  (``auv.cb_height_m=0.02``), or one of its sensor parameters (``arm.noise_std=1e-4``: noise
  and quantization of sensor ports), as if written in the robot declaration
  ``robot auv : auv(cb_height_m = 0.02);`` — checked against the type's declared range;
- ``--set ROBOT.PORT.noise_std=VALUE`` (:class:`NoiseOverride`): the standard deviation of
  the Gaussian noise of sensor port ``PORT`` [the port's unit] (``auv.depth.noise_std=0.05``);
- ``--timing TASK.MODULE.FIELD=MS`` (:class:`TimingOverride`): the period, WCET or BCET [ms]
  of module ``MODULE`` of Robot-Task ``TASK`` at every ``run`` of it, as if written in its
  declaration (``Survey.pilot.wcet_ms=2.5``). With a BCET, execution times are drawn in
  ``[bcet, wcet]`` from the run's seed.

:func:`plan_with_overrides` builds the plan with them: without overrides, the instances
checked when the file was loaded; with some, every run site's Robot-Task instantiated afresh
with the robot declarations' new parameters (:func:`robot_declarations`), then given the new
timings (:func:`timed_instance`) — the loaded instances are never changed, so one compiled
mission serves a whole campaign. :func:`check_overrides` refuses, with a reason, any name the
mission does not have.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, replace
from enum import Enum
from typing import Any, Mapping

from orccad_app.diagnostics import OrccadError
from orccad_app.lang import ast
from orccad_app.lang.limits import MAX_DURATION_NS, MIN_PERIOD_NS
from orccad_app.lang.literals import LiteralError, read_literal
from orccad_app.mission.plan import MissionPlan, plan_composition

__all__ = ["ParamOverride", "NoiseOverride", "TimingOverride", "TimingField", "PlanOverrides",
           "parse_set", "parse_timing", "robot_declarations", "timed_instance",
           "check_overrides", "plan_with_overrides"]

_SET = re.compile(r"^\s*([A-Za-z_]\w*)\.([A-Za-z_]\w*)(?:\.(noise_std))?\s*=\s*(\S+)\s*$")
_TIMING = re.compile(r"^\s*([A-Za-z_]\w*)\.([A-Za-z_]\w*)\.(period_ms|wcet_ms|bcet_ms)\s*="
                     r"\s*(\S+)\s*$")


class TimingField(Enum):
    """Which timing attribute a :class:`TimingOverride` sets."""

    PERIOD = "period_ms"
    WCET = "wcet_ms"
    BCET = "bcet_ms"


@dataclass(frozen=True)
class ParamOverride:
    """``--set ROBOT.PARAM=VALUE``: a robot type parameter."""

    robot: str
    param: str
    value: float | int | bool

    def text(self) -> str:
        """The ``--set`` argument that gives this override."""
        return f"{self.robot}.{self.param}={_number(self.value)}"


@dataclass(frozen=True)
class NoiseOverride:
    """``--set ROBOT.PORT.noise_std=VALUE``: a sensor port's noise [port unit]."""

    robot: str
    port: str
    std: float

    def text(self) -> str:
        return f"{self.robot}.{self.port}.noise_std={_number(self.std)}"


@dataclass(frozen=True)
class TimingOverride:
    """``--timing TASK.MODULE.FIELD=MS``: a Module-Task's period, WCET or BCET."""

    task: str
    module: str
    field: TimingField
    value_ns: int

    def text(self) -> str:
        return f"{self.task}.{self.module}.{self.field.value}={_number(self.value_ns / 1e6)}"


@dataclass(frozen=True)
class PlanOverrides:
    """Every override of one run (empty: the mission as written)."""

    params: tuple[ParamOverride, ...] = ()
    noise: tuple[NoiseOverride, ...] = ()
    timings: tuple[TimingOverride, ...] = ()

    @classmethod
    def from_arguments(cls, sets: list[str], timings: list[str]) -> PlanOverrides:
        """The overrides of ``--set`` and ``--timing`` arguments (raise
        :class:`OrccadError` on a malformed one)."""
        parsed = [parse_set(text) for text in sets]
        return cls(tuple(p for p in parsed if isinstance(p, ParamOverride)),
                   tuple(p for p in parsed if isinstance(p, NoiseOverride)),
                   tuple(parse_timing(text) for text in timings))

    def __bool__(self) -> bool:
        return bool(self.params or self.noise or self.timings)

    def arguments(self) -> list[str]:
        """The ``orccad run`` arguments that give these overrides (``--set``, ``--timing``)."""
        args: list[str] = []
        for item in self.params:
            args += ["--set", item.text()]
        for noise in self.noise:
            args += ["--set", noise.text()]
        for timing in self.timings:
            args += ["--timing", timing.text()]
        return args


def _number(value: Any) -> str:
    """Shortest text that reads back as the same value (``repr`` of a float round-trips)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    return repr(value)


def _scalar(text: str, where: str) -> float | int | bool:
    """A number or true/false (the literal grammar of :mod:`orccad_app.lang.literals`)."""
    try:
        value: float | int | bool = read_literal(text, "scalar")
    except LiteralError as error:
        raise OrccadError(f"{where}: {error.message}") from None
    return value


def parse_set(text: str) -> ParamOverride | NoiseOverride:
    """``ROBOT.PARAM=VALUE`` or ``ROBOT.PORT.noise_std=VALUE``; raise :class:`OrccadError`."""
    match = _SET.match(text)
    if match is None:
        raise OrccadError(f"bad --set {text!r}: expected ROBOT.PARAM=VALUE "
                          f"(auv.cb_height_m=0.02) or ROBOT.PORT.noise_std=VALUE")
    robot, name, noise, raw = match.groups()
    value = _scalar(raw, f"--set {text}")
    if noise:
        if isinstance(value, bool) or not value >= 0:
            raise OrccadError(f"--set {text}: a noise standard deviation must be >= 0")
        return NoiseOverride(robot, name, float(value))
    return ParamOverride(robot, name, value)


def _whole_ns(raw: str, value_ms: float, text: str) -> int:
    """``raw`` ms as a whole number of nanoseconds, exactly (decimal arithmetic); a time that
    is not one is refused, as the language refuses ``1.5 ns`` (never silently rounded)."""
    from decimal import Decimal, InvalidOperation

    try:
        exact = Decimal(raw.replace("_", "")) * 10**6
    except InvalidOperation:  # another spelling _scalar accepted: from its float
        exact = Decimal(value_ms) * 10**6
    if exact != exact.to_integral_value():
        raise OrccadError(f"--timing {text}: {raw} ms is not a whole number of nanoseconds "
                          f"({exact.normalize():f} ns; the language refuses 1.5 ns too)")
    return int(exact)


def parse_timing(text: str) -> TimingOverride:
    """``TASK.MODULE.period_ms|wcet_ms|bcet_ms=MS``; raise :class:`OrccadError`."""
    match = _TIMING.match(text)
    if match is None:
        raise OrccadError(f"bad --timing {text!r}: expected TASK.MODULE.FIELD=MS with FIELD "
                          f"period_ms, wcet_ms or bcet_ms (Survey.pilot.wcet_ms=2.5)")
    task, module, field_name, raw = match.groups()
    value = _scalar(raw, f"--timing {text}")
    if isinstance(value, bool) or not value >= 0:
        raise OrccadError(f"--timing {text}: the time must be a number >= 0 ms")
    field = TimingField(field_name)
    if float(value) * 1e6 > MAX_DURATION_NS:
        raise OrccadError(f"--timing {text}: at most one year (the longest duration)")
    value_ns = _whole_ns(raw.strip(), float(value), text)
    if field is TimingField.PERIOD and value_ns < MIN_PERIOD_NS:
        raise OrccadError(f"--timing {text}: a period must be at least 1 us (0.001 ms), as "
                          "in the language")
    return TimingOverride(task, module, field, value_ns)


def robot_declarations(robots: Mapping[str, Any], host: Any,
                       overrides: PlanOverrides) -> dict[str, Any]:
    """The program's robot declarations (``ast.Robot``) with the ``--set`` parameters added
    as arguments; each override is checked against the robot type's declared parameter."""
    result = dict(robots)
    for item in overrides.params:
        robot = result.get(item.robot)
        if robot is None:
            raise OrccadError(f"--set {item.text()}: no robot '{item.robot}' "
                              f"(robots: {', '.join(robots) or 'none'})")
        robot_type = host.robot_types.get(robot.type)
        _check_param(robot_type, item)
        args = tuple(a for a in robot.args if a.name != item.param)
        literal = (ast.Bool(value=item.value) if isinstance(item.value, bool)
                   else ast.Number(value=item.value, text=repr(item.value)))
        result[item.robot] = replace(robot, args=args + (ast.Arg(name=item.param, value=literal),))
    return result


def _check_param(robot_type: Any, item: ParamOverride) -> None:
    from orccad_app.control.params import close_matches

    specs = {spec.name: spec for spec in robot_type.parameters}
    spec = specs.get(item.param)
    if spec is None:
        raise OrccadError(f"--set {item.text()}: robot type '{robot_type.name}' declares no "
                          f"parameter '{item.param}'{close_matches(item.param, list(specs))} "
                          f"(parameters: {', '.join(specs) or 'none'})")
    try:
        spec.coerce(item.value, robot_type.name)
    except OrccadError as error:
        raise OrccadError(f"--set {item.text()}: {error.message}") from None


def timed_instance(instance: Any, task: str, overrides: PlanOverrides) -> Any:
    """``instance`` (a ``TaskInstance`` of Robot-Task ``task``) with the ``--timing``
    overrides of ``task`` applied to its modules' timing (the instance is updated)."""
    from orccad_app.control.module import Timing

    for item in overrides.timings:
        if item.task != task:
            continue
        spec = instance.modules.get(item.module)
        if spec is None:
            raise OrccadError(f"--timing {item.text()}: Robot-Task '{task}' has no module "
                              f"'{item.module}' (modules: {', '.join(instance.modules)})")
        old = spec.timing
        values = {"period_ns": old.period_ns, "wcet_ns": old.wcet_ns, "bcet_ns": old.bcet_ns}
        key = {TimingField.PERIOD: "period_ns", TimingField.WCET: "wcet_ns",
               TimingField.BCET: "bcet_ns"}[item.field]
        values[key] = item.value_ns
        if values["bcet_ns"] is not None and values["bcet_ns"] > values["wcet_ns"]:
            raise OrccadError(f"--timing {item.text()}: the BCET of {task}.{item.module} "
                              f"({values['bcet_ns'] / 1e6:g} ms) exceeds its WCET "
                              f"({values['wcet_ns'] / 1e6:g} ms)")
        spec.timing = Timing(**values)
    return instance


def check_overrides(overrides: PlanOverrides, tasks: set[str],
                    robot_types: Mapping[str, Any]) -> None:
    """Refuse timing overrides of Robot-Tasks the mission does not run and noise overrides
    of robots or sensor ports it does not have."""
    for item in overrides.timings:
        if item.task not in tasks:
            raise OrccadError(f"--timing {item.text()}: the mission runs no Robot-Task "
                              f"'{item.task}' (it runs: {', '.join(sorted(tasks))})")
    for noise in overrides.noise:
        robot_type = robot_types.get(noise.robot)
        if robot_type is None:
            raise OrccadError(f"--set {noise.text()}: the mission has no robot "
                              f"'{noise.robot}' (robots: {', '.join(robot_types)})")
        sensors = [port.name for port in robot_type.sensors]
        if noise.port not in sensors:
            raise OrccadError(f"--set {noise.text()}: robot '{noise.robot}' has no sensor "
                              f"port '{noise.port}' (sensors: {', '.join(sensors)})")
        bound, why = noise_bound(robot_type, noise.port)
        if noise.std > bound:
            raise OrccadError(f"--set {noise.text()}: a noise standard deviation of at most "
                              f"{bound:g} is accepted on {noise.robot}.{noise.port} ({why})")


#: Largest noise standard deviation of a sensor port that no parameter of its robot type
#: bounds [the port's unit]: larger noise overflows the samples (1e308 gives infinities).
MAX_NOISE_STD = 1e6


def noise_bound(robot_type: Any, port: str) -> tuple[float, str]:
    """The largest noise standard deviation ``--set ROBOT.PORT.noise_std`` accepts on
    ``port``, and why: the maximum of the robot type's noise parameter of that port, else
    :data:`MAX_NOISE_STD`."""
    for param in getattr(robot_type, "sensor_params", ()):
        if param.setting.value == "noise_std" and port in param.ports \
                and param.maximum is not None:
            return float(param.maximum), f"the bound of {robot_type.name}'s {param.name}"
    return MAX_NOISE_STD, "larger noise overflows the samples"


def plan_with_overrides(source: Any, mission: ast.Mission, overrides: PlanOverrides,
                        composition: Any = None) -> MissionPlan:
    """The plan of ``mission`` of ``source`` (a loaded :class:`~orccad_app.pipeline.Source`)
    with ``overrides`` (see the module docstring); ``composition``: the mission's
    :class:`~orccad_app.robottask.composition.Composition` when the caller has it already."""
    from orccad_app.pipeline import compose_mission
    from orccad_app.plugin_host.host import PluginHost
    from orccad_app.robottask.model import instantiate

    composition = composition or compose_mission(source, mission, lazy=True)
    if not overrides:
        instances = {site.number: source.instance(site.stmt) for site in composition.sites}
        return plan_composition(composition, instances)
    host = source.host if source.host is not None else PluginHost.load()
    robots = robot_declarations({r.name: r for r in source.program.robots}, host, overrides)
    instances = {}
    for site in composition.sites:
        instance = instantiate(site.robottask, robots, host, site.stmt.args, site.stmt.loc)
        instances[site.number] = timed_instance(instance, site.task, overrides)
    plan = plan_composition(composition, instances)
    types = {spec.robot: spec.robot_type for spec in plan.plants}
    check_overrides(overrides, {site.task for site in composition.sites}, types)
    noise = {(n.robot, n.port): n.std for n in overrides.noise}
    plan.plants = [replace(spec, noise_std={**spec.noise_std,
                                            **{p: v for (r, p), v in noise.items()
                                               if r == spec.robot}})
                   for spec in plan.plants]
    return plan
