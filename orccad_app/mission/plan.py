"""What a mission needs to run: its automaton, one TCS for every ``run`` site, the plants.

:func:`plan_mission` takes a mission's :class:`~orccad_app.robottask.composition.Composition`
(the composed automaton, its run sites, the roles of its signals) and the checked Robot-Task
instance of every run site (made once, when the file was loaded), and puts all of their
Module-Tasks in **one** TCS, idle until the behaviour automata activate them:

- the Module-Tasks of site ``s`` of task ``X`` are named ``X.module`` (``X_s.module`` when ``X``
  is run at several sites, ``s`` the site number);
- one plant per robot (:class:`PlantSpec`), built from its robot type's MJCF file, with the
  sensors' noise and quantization (the ports' defaults, or the values of the robot type's
  sensor parameters: ``robot arm : arm3dof(noise_std = 1e-4);``). **Initial state:** at rest, on the reference at
  ``t = 0`` of the first Robot-Task run on that robot when its task function is a joint-space
  reference with a known start (RR-1801 §7.1 starts on the trajectory); else the model's
  ``qpos0``;
- observer events: a written event port ``X.module.event`` is the automaton input ``X.E``
  (``E`` the exception or condition it serves, :attr:`RobotTaskInstance.events`).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from math import gcd
from typing import Any, Mapping

import numpy as np

from orccad_app.control.module import ModuleInstance
from orccad_app.control.ports import TASK_ERROR
from orccad_app.diagnostics import OrccadError, SourceLocation
from orccad_app.executive.plant import MujocoPlant, PlantExtension
from orccad_app.lang import ast
from orccad_app.mission.tcs_bridge import add_instance, robot_resource
from orccad_app.pipeline import Source, compose_mission
from orccad_app.reactive.automaton import Automaton
from orccad_app.reactive.lazy import LazyAutomaton
from orccad_app.robottask.application import RunSite
from orccad_app.robottask.composition import Composition
from orccad_app.robottask.labels import Phase
from orccad_app.robottask.model import DEFAULT_PROCESSOR, RobotTaskInstance
from orccad_app.robottask.run_arguments import RunArgument
from orccad_app.robottask.signals import RoleKind, SignalRoles
from orccad_app.robottask.updates import UpdateForm
from orccad_app.tcs.graph import TCS
from orccad_app.tcs.port import PortRef

__all__ = ["SiteModules", "ParamUpdate", "PlantSpec", "MissionPlan", "plan_mission",
           "plan_composition"]


@dataclass(frozen=True)
class ParamUpdate:
    """A type-1 exception's update of a Module-Task parameter, in TCS names.

    :param module: the TCS Module-Task.
    :param param: the parameter.
    :param value: its new value when constant (``None`` when computed or a ramp).
    :param form: the value as written: an expression over the current parameters, or a ramp
        (:class:`~orccad_app.robottask.updates.UpdateForm`); ``None``: ``value``.
    :param env: the Robot-Task's parameters (names in the expression).
    :param modules: the task's module names -> TCS Module-Tasks (``ctrl`` -> ``X.ctrl``).
    :param loc: the ``adjust`` clause.
    """

    module: str
    param: str
    value: Any
    form: UpdateForm | None = None
    env: Mapping[str, Any] = field(default_factory=dict)
    modules: Mapping[str, str] = field(default_factory=dict)
    loc: SourceLocation | None = None


@dataclass
class SiteModules:
    """The Robot-Task instance of one run site, placed in the mission's TCS.

    :param site: the run site.
    :param instance: its checked Robot-Task instance.
    :param modules: TCS names of every Module-Task (phase 3), in declaration order.
    :param measuring: TCS names of the modules active from phase 2.
    :param events: TCS signal ``X.module.port`` -> automaton input ``X.E``.
    :param adjustments: exception ``E`` -> its type-1 parameter update.
    :param error_module: the TCS module writing the task error ``e`` (tracking error), if any.
    :param start_signal: the automaton output that (re)starts the task (``X.start``).
    :param good_end_signal: the automaton output of its good end (``X.good_end``).
    :param error_unit: the unit of its task error (``rad``, ``m`` for a Cartesian position).
    :param event_ports: automaton input ``X.E`` -> the observer port that raises it (TCS
        module, port).
    """

    site: RunSite
    instance: RobotTaskInstance
    modules: tuple[str, ...]
    measuring: tuple[str, ...]
    events: dict[str, str] = field(default_factory=dict)
    adjustments: dict[str, ParamUpdate] = field(default_factory=dict)
    error_module: str | None = None
    start_signal: str | None = None
    good_end_signal: str | None = None
    error_unit: str = "rad"
    event_ports: dict[str, PortRef] = field(default_factory=dict)

    @property
    def number(self) -> int:
        """The run site's number."""
        return self.site.number

    @property
    def task(self) -> str:
        """The Robot-Task's name."""
        return self.site.task

    @property
    def automaton_processor(self) -> str:
        """The processor its behaviour automaton reacts on: declared (``automaton on P``),
        else its first module's."""
        placement = self.instance.task.automaton
        if placement is not None:
            return placement.processor
        first = next(iter(self.instance.modules.values()), None)
        return first.processor if first is not None else DEFAULT_PROCESSOR

    @property
    def reaction_ns(self) -> int:
        """The execution time of one reaction of its automaton [ns] (0 unless declared)."""
        placement = self.instance.task.automaton
        return placement.reaction_ns if placement is not None else 0

    @property
    def arguments(self) -> tuple[RunArgument, ...]:
        """The run site's run-time arguments (evaluated when the task starts)."""
        return self.site.arguments

    def bound(self, values: Mapping[str, Any]) -> RobotTaskInstance:
        """The instance of this start: the checked one, or, with run-time arguments, the one
        bound to their values (``values``: automaton output -> value in the starting
        instant); raises :class:`~orccad_app.robottask.binding.ArgumentError`."""
        if not self.site.arguments:
            return self.instance
        from orccad_app.robottask.binding import bind_arguments
        return bind_arguments(self.instance, self.site.arguments, values)

    def fresh_computes(self, instance: RobotTaskInstance | None = None
                       ) -> dict[str, ModuleInstance]:
        """New compute objects for every module (nominal parameters: a Robot-Task run again
        does not inherit the type-1 updates of its previous run); ``instance``: the bound
        instance of this start (default: the checked one)."""
        instance = instance or self.instance
        specs = instance.modules.values()
        return {name: spec.fresh(instance.context) for name, spec in zip(self.modules, specs)}

    def adjustments_of(self, instance: RobotTaskInstance) -> dict[str, ParamUpdate]:
        """The type-1 updates of ``instance`` (a bound instance of this site), in TCS names."""
        if instance is self.instance:
            return self.adjustments
        return _param_updates(instance, dict(zip(instance.modules, self.modules)))

    def wanted(self, phase: int) -> tuple[str, ...]:
        """Modules active in ``phase`` (0: not running)."""
        if phase >= Phase.ACTIVE:
            return self.modules
        return self.measuring if phase == Phase.MEASURING else ()


@dataclass(frozen=True)
class PlantSpec:
    """How to build one robot's plant for a run (each run builds its own).

    :param robot: the robot's name (the TCS physical resource).
    :param path: its MJCF file.
    :param noise_std: sensor port -> standard deviation of its noise (port unit).
    :param quantization: sensor port -> quantization step (port unit).
    :param qpos0: initial joint positions [rad or m], ``None`` for the model's.
    :param robot_type: the robot type (its plant extension, its run horizon).
    """

    robot: str
    path: str
    noise_std: dict[str, float]
    quantization: dict[str, float]
    qpos0: np.ndarray | None
    robot_type: Any

    def build(self) -> MujocoPlant:
        """A fresh plant, with the robot type's plant extension when it has one."""
        extension: PlantExtension | None = self.robot_type.plant_extension()
        return MujocoPlant(self.robot, path=self.path, noise_std=self.noise_std,
                           quantization=self.quantization, qpos0=self.qpos0,
                           extension=extension, idle=self.robot_type.idle,
                           idle_gains=self.robot_type.idle_gains)


@dataclass
class MissionPlan:
    """A mission ready for :class:`~orccad_app.mission.run.MissionRun`.

    :param name: the mission's name.
    :param automaton: its composed automaton (built on demand for a run).
    :param roles: the role of every signal the lowering added.
    :param sites: per ``run`` site, in site order.
    :param tcs: one TCS holding every site's Module-Tasks and the robots.
    :param plants: per robot, how to build its plant.
    :param tick_ns: the automaton's periodic reaction [ns] (the gcd of the module periods).
    """

    name: str
    automaton: Automaton | LazyAutomaton
    roles: SignalRoles
    sites: list[SiteModules]
    tcs: TCS
    plants: list[PlantSpec]
    tick_ns: int

    @property
    def signals(self) -> dict[str, str]:
        """Every TCS event signal -> automaton input."""
        return {signal: name for site in self.sites for signal, name in site.events.items()}

    @property
    def processor_names(self) -> tuple[str, ...]:
        """Every processor of the run: the Module-Tasks', then the automata's, first-seen
        order."""
        names = [task.processor for task in self.tcs.module_tasks]
        names += [site.automaton_processor for site in self.sites]
        return tuple(dict.fromkeys(names))

    def run_horizon_s(self, default_s: float) -> float:
        """The default simulated-time limit [s]: ``default_s``, or longer when a robot type
        declares a longer ``run_horizon_s`` (an AUV mission lasts minutes)."""
        return max([default_s, *(p.robot_type.run_horizon_s or 0.0 for p in self.plants)])


def _prefixes(sites: tuple[RunSite, ...]) -> list[str]:
    counts: dict[str, int] = {}
    for site in sites:
        counts[site.task] = counts.get(site.task, 0) + 1
    return [f"{s.task}." if counts[s.task] == 1 else f"{s.task}_{s.number}." for s in sites]


def _param_updates(instance: RobotTaskInstance, names: dict[str, str]) -> dict[str, ParamUpdate]:
    """The type-1 updates of ``instance``, in TCS names (``names``: its modules -> TCS)."""
    return {e: ParamUpdate(names[a.module], a.param, a.value, a.form, instance.params, names,
                           a.loc)
            for e, a in instance.adjustments.items()}


def _site_modules(site: RunSite, instance: RobotTaskInstance, names: dict[str, str],
                  inputs: set[str], roles: SignalRoles) -> SiteModules:
    task = site.task
    events, event_ports = {}, {}
    for event, ref in instance.events.items():
        name = f"{task}.{event}"
        if name in inputs:
            port = event_ports[name] = PortRef(names[ref.module], ref.port)
            events[str(port)] = name
    adjustments = _param_updates(instance, names)
    error = next((names[n] for n, spec in instance.modules.items()
                  if any(p.name == TASK_ERROR and p.direction == "out"
                         for p in spec.instance.ports)),
                 None)
    unit = _error_unit(instance)
    return SiteModules(site, instance, tuple(names.values()),
                       tuple(names[m] for m in instance.measuring), events, adjustments, error,
                       roles.signal(RoleKind.START, task), roles.signal(RoleKind.GOOD_END, task),
                       unit, event_ports)


def _error_unit(instance: RobotTaskInstance) -> str:
    """The unit of the task error ``e`` of ``instance``'s task function (``rad`` without one)."""
    context = instance.context
    if context.task_function is None or context.robot is None:
        return "rad"
    return context.task_function.build(context.robot).error_unit


def _initial_q(instance: RobotTaskInstance) -> np.ndarray | None:
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


def _plant_spec(robot: str, robot_type: Any, qpos0: np.ndarray | None) -> PlantSpec:
    noise = {port: std for port, std in robot_type.sensor_noise().items() if std}
    quanta = {port: step for port, step in robot_type.sensor_quantization().items() if step}
    return PlantSpec(robot, str(robot_type.mjcf_path), noise, quanta, qpos0, robot_type)


def plan_composition(composition: Composition,
                     instances: dict[int, RobotTaskInstance]) -> MissionPlan:
    """The plan of a composed mission whose run site ``n`` runs ``instances[n]``."""
    mission = composition.mission
    inputs = {s.name for s in composition.automaton.inputs}
    tcs = TCS(mission.name, shared_actuators=True)
    plants: dict[str, PlantSpec] = {}
    sites = []
    for site, prefix in zip(composition.sites, _prefixes(composition.sites)):
        instance = instances[site.number]
        robot = instance.robot_name
        if robot not in plants:
            robot_type = instance.context.require_robot(f"Robot-Task '{site.task}'")
            plants[robot] = _plant_spec(robot, robot_type, _initial_q(instance))
            tcs.add(robot_resource(robot, robot_type))
        names = add_instance(tcs, instance, prefix)
        sites.append(_site_modules(site, instance, names, inputs, composition.roles))
    if not sites:
        raise OrccadError(f"mission '{mission.name}' runs no Robot-Task: nothing to execute "
                          f"(use 'orccad react' for the automaton alone)", mission.loc)
    tick = _reaction_tick_ns(tcs, mission)
    return MissionPlan(mission.name, composition.automaton, composition.roles, sites, tcs,
                       list(plants.values()), tick)


#: The automaton's periodic reaction may be at most this many times finer than the fastest
#: Module-Task period: a finer tick would cost more reactions than the jobs themselves.
MAX_TICKS_PER_PERIOD = 1000


def _reaction_tick_ns(tcs: TCS, mission: ast.Mission) -> int:
    """The gcd of the Module-Task periods [ns], the instant period of the automaton's timers;
    refused (a cost budget, failing fast) when it is far finer than every period."""
    tick = 0
    for task in tcs.module_tasks:
        tick = gcd(tick, task.period_ns)
    fastest = min((task.period_ns for task in tcs.module_tasks), default=tick)
    if tick and fastest // tick > MAX_TICKS_PER_PERIOD:
        periods = sorted({task.period_ns for task in tcs.module_tasks})
        raise OrccadError(
            f"the Module-Task periods ({', '.join(f'{p} ns' for p in periods)}) have a "
            f"greatest common divisor of {tick} ns, {fastest // tick}x finer than the fastest "
            f"period: the mission's timers react at that divisor, and a run would cost that "
            f"many reactions (at most {MAX_TICKS_PER_PERIOD}x is accepted); choose "
            f"commensurate periods, e.g. whole milliseconds", mission.loc)
    return tick


def plan_mission(source: Source, mission: ast.Mission) -> MissionPlan:
    """Compose ``mission`` of ``source`` and plan it with the instances checked at load."""
    composition = compose_mission(source, mission, lazy=True)
    instances = {site.number: source.instance(site.stmt) for site in composition.sites}
    return plan_composition(composition, instances)
