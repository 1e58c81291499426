"""What a mission needs to run: its automaton, one TCS for every ``run`` site, the plants.

:func:`plan_mission` compiles the mission's composed automaton (the application and the RTAs
of its Robot-Tasks, :func:`~orccad_app.pipeline.compile_mission_sites`), instantiates the
Robot-Task of every ``run`` statement with that statement's arguments, and puts all of their
Module-Tasks in **one** TCS, idle until the behaviour automata activate them:

- the Module-Tasks of site ``s`` of task ``X`` are named ``X.module`` (``X_s.module`` when ``X``
  is run at several sites, ``s`` the site number);
- one :class:`~orccad_app.executive.plant.MujocoPlant` per robot, built from its robot type's
  MJCF file, with the sensors' default noise and quantization. **Initial state:** at rest, on
  the reference at ``t = 0`` of the first Robot-Task run on that robot when its task function
  is a joint-space reference with a known start (RR-1801 §7.1 starts on the trajectory); else
  the model's ``qpos0``;
- observer events: a written event port ``X.module.event`` is the automaton input ``X.E``
  (``E`` the exception or condition it serves, :attr:`TaskInstance.events`).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from math import gcd
from typing import Any

import numpy as np

from orccad_app.diagnostics import OrccadError
from orccad_app.executive.plan_overrides import (PlanOverrides, check_overrides,
                                                 robot_declarations, timed_instance)
from orccad_app.executive.plant import MujocoPlant
from orccad_app.executive.task_tcs import add_instance, robot_resource
from orccad_app.tcs.graph import TCS

__all__ = ["SitePlan", "MissionPlan", "plan_mission"]


@dataclass
class SitePlan:
    """One ``run X(args)`` of the mission and its Module-Tasks.

    :param site: the site number (``("rt", X, site)`` labels).
    :param task: the Robot-Task's name ``X``.
    :param instance: the checked task instance (``TaskInstance``).
    :param modules: TCS names of every Module-Task (phase 3), in declaration order.
    :param measuring: TCS names of the modules active from phase 2.
    :param events: TCS signal ``X.module.port`` -> automaton input ``X.E``.
    :param adjustments: exception ``E`` -> ``(TCS module, parameter, value)`` (type 1).
    :param exception_types: exception name -> 1, 2 or 3 (RR-1801 §3.4.2).
    :param error_module: the TCS module writing the task error ``e`` (tracking error), if any.
    """

    site: int
    task: str
    instance: Any
    modules: tuple[str, ...]
    measuring: tuple[str, ...]
    events: dict[str, str] = field(default_factory=dict)
    adjustments: dict[str, tuple[str, str, Any]] = field(default_factory=dict)
    exception_types: dict[str, int] = field(default_factory=dict)
    error_module: str | None = None

    def fresh_computes(self) -> dict[str, Any]:
        """New compute objects for every module (nominal parameters: a Robot-Task run again
        does not inherit the type-1 updates of its previous run)."""
        specs = self.instance.modules.values()
        return {name: spec.fresh(self.instance.context) for name, spec in zip(self.modules, specs)}

    def wanted(self, phase: int) -> tuple[str, ...]:
        """Modules active in ``phase`` (0: not running)."""
        if phase >= 3:
            return self.modules
        return self.measuring if phase == 2 else ()


@dataclass
class MissionPlan:
    """A mission ready for :class:`~orccad_app.executive.mission_run.MissionRun`.

    :param name: the mission's name.
    :param automaton: its composed automaton.
    :param sites: per ``run`` site, in site order.
    :param tcs: one TCS holding every site's Module-Tasks and the robots.
    :param plant_specs: robot name -> keyword arguments of :class:`MujocoPlant`.
    :param tick_ns: the automaton's periodic reaction [ns] (the gcd of the module periods).
    """

    name: str
    automaton: Any
    sites: list[SitePlan]
    tcs: TCS
    plant_specs: dict[str, dict[str, Any]]
    tick_ns: int

    def plants(self) -> list[MujocoPlant]:
        """Fresh plants, one per robot (each run needs its own)."""
        return [MujocoPlant(name, **spec) for name, spec in self.plant_specs.items()]

    @property
    def signals(self) -> dict[str, str]:
        """Every TCS event signal -> automaton input."""
        return {signal: name for site in self.sites for signal, name in site.events.items()}


def _prefixes(sites: list) -> list[str]:
    counts: dict[str, int] = {}
    for site in sites:
        counts[site.task.name] = counts.get(site.task.name, 0) + 1
    return [f"{s.task.name}." if counts[s.task.name] == 1 else f"{s.task.name}_{s.number}."
            for s in sites]


def _site_plan(site: Any, instance: Any, names: dict[str, str], inputs: set[str]) -> SitePlan:
    task = site.task.name
    events = {}
    for event, (module, port) in instance.events.items():
        name = f"{task}.{event}"
        if name in inputs:
            events[f"{names[module]}.{port}"] = name
    adjustments = {e: (names[a.module], a.param, a.value)
                   for e, a in instance.adjustments.items()}
    types = {e.name: e.type.number for e in site.task.exceptions}
    error = next((names[n] for n, spec in instance.modules.items()
                  if any(p.name == "e" and p.direction == "out" for p in spec.instance.ports)),
                 None)
    return SitePlan(site.number, task, instance, tuple(names.values()),
                    tuple(names[m] for m in instance.measuring), events, adjustments, types,
                    error)


def _initial_q(instance: Any) -> np.ndarray | None:
    """``q_d(0)`` of a joint-space task function with a known start, else ``None``."""
    context = instance.context
    if context.task_function is None or context.robot is None:
        return None
    function = context.task_function.build(context.robot)
    if getattr(function.trajectory, "needs_start", False) or function.dim != context.robot.dof:
        return None
    if function.reference_name != "qd":
        return None
    return np.asarray(function.reference(0.0).pos, dtype=float)


def _plant_spec(robot_type: Any, qpos0: np.ndarray | None) -> dict[str, Any]:
    noise = {p.name: p.noise_std for p in robot_type.sensors if p.noise_std}
    quanta = {p.name: p.quantum for p in robot_type.sensors if p.quantum}
    return {"path": str(robot_type.mjcf_path), "noise_std": noise, "quantization": quanta,
            "qpos0": qpos0}


def plan_mission(source: Any, mission: Any, host: Any = None, *,
                 overrides: PlanOverrides | None = None,
                 compiled: tuple[Any, list] | None = None) -> MissionPlan:
    """Compile ``mission`` of ``source`` (a :class:`~orccad_app.pipeline.Source`) and build
    the TCS and plants of all its ``run`` sites, with ``overrides`` (``--set``,
    ``--timing``: :mod:`~orccad_app.executive.plan_overrides`) applied. ``compiled``: the
    ``(automaton, sites)`` of :func:`~orccad_app.pipeline.compile_mission_sites` when the
    caller already has them (a campaign compiles once, plans each run)."""
    from orccad_app.pipeline import compile_mission_sites
    from orccad_app.robottask.model import instantiate

    if host is None:
        from orccad_app.plugins.host import default_host
        host = default_host()
    overrides = overrides or PlanOverrides()
    automaton, sites = compiled or compile_mission_sites(source, mission)
    robots = robot_declarations({r.name: r for r in source.program.robots}, host, overrides)
    inputs = {s.name for s in automaton.inputs}
    tcs = TCS(mission.name, shared_actuators=True)
    plant_specs: dict[str, dict[str, Any]] = {}
    types: dict[str, Any] = {}
    plans = []
    for site, prefix in zip(sites, _prefixes(sites)):
        instance = instantiate(site.task, robots, host, site.stmt.args, site.stmt.loc)
        timed_instance(instance, site.task.name, overrides)
        robot = instance.robot_name
        if robot not in plant_specs:
            robot_type = instance.context.robot
            plant_specs[robot] = _plant_spec(robot_type, _initial_q(instance))
            types[robot] = robot_type
            tcs.add(robot_resource(robot, robot_type))
        names = add_instance(tcs, instance, prefix)
        plans.append(_site_plan(site, instance, names, inputs))
    if not plans:
        raise OrccadError(f"mission '{mission.name}' runs no Robot-Task: nothing to execute "
                          f"(use 'orccad react' for the automaton alone)", mission.loc)
    check_overrides(overrides, {site.task.name for site in sites}, types)
    for noise in overrides.noise:
        plant_specs[noise.robot]["noise_std"][noise.port] = noise.std
    tick = 0
    for task in tcs.module_tasks:
        tick = gcd(tick, task.period_ns)
    return MissionPlan(mission.name, automaton, plans, tcs, plant_specs, tick)
