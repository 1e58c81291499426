"""A Robot-Task instantiated against the plugin registries: its checked control scheme.

:func:`instantiate` turns a ``robottask`` block and the arguments of one ``run`` into a
:class:`RobotTaskInstance`: the robot type, the control law and task function (their coherence
checks — ``dim e = dim q``, positive gains, shapes — run here), every Module-Task with its
kind, parameters and timing, the observers named by exceptions and conditions (a declared
module, or an observer kind instantiated with its default timing), and the connections,
checked: ports exist, producer to consumer, same type and dimension, each input fed once,
required inputs fed. Every error names the bad value and carries the clause's location.

The mission layer builds its Module-Tasks from a :class:`RobotTaskInstance`; the compiler
instantiates every task once per ``run`` site (:func:`check_tasks`) so that each set of
arguments is checked, and the mission layer runs those very instances.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from enum import Enum
from typing import Any, Mapping

from orccad_app.control.module import ModuleContext, ModuleInstance, ModuleKind, Timing
from orccad_app.control.spec import module_context, resolve
from orccad_app.diagnostics import Diagnostic, OrccadError, SourceLocation
from orccad_app.lang import ast
from orccad_app.lang.walk import runs
from orccad_app.robottask.updates import UpdateForm, compute, update_form
from orccad_app.robottask.values import call_form, task_arguments
from orccad_app.robottask.wiring import Endpoint, wire
from orccad_app.tcs.phasing import Activation
from orccad_app.tcs.port import PortRef

__all__ = ["ModuleOrigin", "ModuleSpec", "Adjustment", "RobotTaskInstance", "TaskInstances",
           "instantiate", "check_tasks",
           "DEFAULT_PROCESSOR"]

DEFAULT_PROCESSOR = "cpu0"


class ModuleOrigin(Enum):
    """Why a Module-Task is in a task instance."""

    DECLARED = "declared"      # a 'module' clause
    OBSERVER = "observer"      # made for an observer named in 'from' or a condition
    LAW_DEFAULT = "law default"  # the law's default scheme, for a kind the task omits


@dataclass
class ModuleSpec:
    """One Module-Task of a task instance."""

    name: str
    kind: ModuleKind
    instance: ModuleInstance
    timing: Timing
    processor: str
    priority: int
    loc: SourceLocation
    origin: ModuleOrigin = ModuleOrigin.DECLARED
    params: dict = field(default_factory=dict)  # as given, for a fresh instance
    activation: Activation = Activation.PERIODIC
    """Periodic, or sporadic (``timing.period_ns`` is then its minimum inter-arrival time)."""

    @property
    def implicit(self) -> bool:
        """Made by the compiler (not declared): its ports are wired by name."""
        return self.origin is not ModuleOrigin.DECLARED

    def fresh(self, context: ModuleContext) -> ModuleInstance:
        """A new instance with the same parameters (the executive makes one per run)."""
        return self.kind.create(self.params, context)


@dataclass(frozen=True)
class Adjustment:
    """A type-1 exception's parameter update: ``module.param = value``.

    :param exception: the exception.
    :param module: the Module-Task whose parameter changes.
    :param param: the parameter.
    :param value: the new value when it is a constant expression (checked), else ``None``.
    :param form: the value as written (:class:`~orccad_app.robottask.updates.UpdateForm`):
        an expression, possibly over other parameters' current values, or a ramp.
    :param loc: the ``adjust`` clause (run-time errors of the update point at it).
    """

    exception: str
    module: str
    param: str
    value: Any
    form: UpdateForm | None = None
    loc: SourceLocation | None = None


@dataclass
class RobotTaskInstance:
    """A Robot-Task ready to run: modules, connections, events, adjustments."""

    task: ast.RobotTask
    params: dict[str, Any]
    robot_name: str
    context: ModuleContext
    modules: dict[str, ModuleSpec] = field(default_factory=dict)
    connections: list = field(default_factory=list)
    events: dict[str, PortRef] = field(default_factory=dict)  # event -> its observer's port
    adjustments: dict[str, Adjustment] = field(default_factory=dict)
    measuring: tuple[str, ...] = ()  # modules active from phase 2 (measurement pre-conditions)
    #: what :func:`instantiate` was given, to bind the run-time arguments again at each start
    robots: Mapping[str, ast.Robot] = field(default_factory=dict, repr=False)
    host: Any = field(default=None, repr=False)
    args: tuple[ast.Arg, ...] = ()
    run_loc: SourceLocation | None = None

    @property
    def duration_s(self) -> float | None:
        ns = self.task.duration_ns
        return None if ns is None else ns / 1e9


def _located(error: OrccadError, loc: SourceLocation) -> OrccadError:
    if error.location is None or error.location.line <= 0:
        return OrccadError(error.message, loc, error.notes)
    return error


def _context(task: ast.RobotTask, params: dict, robots: Mapping[str, ast.Robot], host):
    robot = robots.get(task.robot)
    if robot is None:
        raise OrccadError(f"unknown robot '{task.robot}'", task.loc)
    try:
        robot_type = host.robot_types.get(robot.type)
        robot_args = call_form(ast.Call(func=robot.type, args=robot.args), {})[1]
        if robot_args:
            robot_type = robot_type.configure(robot_args)
    except OrccadError as error:
        raise _located(error, robot.loc) from None
    function = task.task_function
    tf = None if function is None else call_form(function, params)
    law = None if task.law is None else call_form(task.law, params)
    if function is not None and tf is not None:
        try:
            resolve(host, "task function", tf)
        except OrccadError as error:
            raise _located(error, function.loc) from None
    try:
        return module_context(host, robot_type, tf, law, task.duration_ns and
                              task.duration_ns / 1e9, task.robot)
    except OrccadError as error:  # point at the clause the message is about
        clause = task.task_function if tf and error.message.startswith(tf[0]) else task.law
        raise _located(error, (clause or task).loc) from None


def _declared_modules(task: ast.RobotTask, params: dict, context, host) -> dict[str, ModuleSpec]:
    modules: dict[str, ModuleSpec] = {}
    for m in task.modules:
        try:
            kind = host.module_kind(m.kind)
            if any(a.name is None for a in m.args):
                raise OrccadError(f"arguments of module kind '{m.kind}' must be named", m.loc)
            values = call_form(ast.Call(func=m.kind, args=m.args), params)[1]
            instance = kind.create(values, context)
            default = kind.default_timing
            if m.min_interarrival_ns is not None and m.period_ns is not None:
                raise OrccadError(f"module '{m.name}' is sporadic: give its minimum "
                                  f"inter-arrival time or a period, not both", m.loc)
            timing = Timing(m.min_interarrival_ns or m.period_ns or default.period_ns,
                            m.wcet_ns if m.wcet_ns is not None else default.wcet_ns,
                            m.bcet_ns if m.bcet_ns is not None else None)
        except OrccadError as error:
            raise _located(error, m.loc) from None
        if m.priority is not None and m.priority < 1:
            raise OrccadError(f"priority of module '{m.name}' must be ≥ 1 (1 is the highest), "
                              f"got {m.priority}", m.loc)
        modules[m.name] = ModuleSpec(m.name, kind, instance, timing,
                                     m.processor or DEFAULT_PROCESSOR, m.priority or 0, m.loc,
                                     params=values,
                                     activation=Activation.PERIODIC
                                     if m.min_interarrival_ns is None else Activation.SPORADIC)
    return modules


def _unique(name: str, modules: Mapping[str, ModuleSpec]) -> str:
    base, n = name, 2
    while name in modules:
        name, n = f"{base}_{n}", n + 1
    return name


def _law_defaults(inst: RobotTaskInstance, host) -> None:
    """The law's default Module-Tasks whose kind the task does not declare (the omitted
    parts of the time-constrained specification)."""
    law = inst.task.law
    if law is None:
        return
    declared = {spec.kind.name for spec in inst.modules.values()}
    processor = next(iter(inst.modules.values())).processor if inst.modules else DEFAULT_PROCESSOR
    for default in host.control_laws.get(law.func).default_modules:
        if default.kind in declared:
            continue
        try:
            kind = host.module_kind(default.kind)
            instance = kind.create({}, inst.context)
        except OrccadError as error:
            raise _located(error, law.loc) from None
        name = _unique(default.name, inst.modules)
        inst.modules[name] = ModuleSpec(name, kind, instance, kind.default_timing, processor, 0,
                                        law.loc, origin=ModuleOrigin.LAW_DEFAULT)


def _observer(call: ast.Call, loc: SourceLocation, inst: RobotTaskInstance, host) -> str:
    """The module watching for a condition or exception: declared, or made from a kind."""
    declared = inst.modules.get(call.func)
    if declared is not None and not call.args:
        if not declared.kind.is_observer:
            raise OrccadError(f"module '{call.func}' ({declared.kind.name}) is not an observer: "
                              "it has no event output", call.loc)
        return call.func
    try:
        kind = host.observers.get(call.func)
        values = call_form(call, inst.params)[1]
        instance = kind.create(values, inst.context)
    except OrccadError as error:
        raise _located(error, call.loc) from None
    name = _unique(call.func, inst.modules)
    processor = next(iter(inst.modules.values())).processor if inst.modules else DEFAULT_PROCESSOR
    inst.modules[name] = ModuleSpec(name, kind, instance, kind.default_timing, processor, 0,
                                    loc, origin=ModuleOrigin.OBSERVER, params=values)
    return name


def _conditions(inst: RobotTaskInstance, host) -> None:
    task = inst.task
    measuring = []
    for pre in task.preconditions:
        if isinstance(pre, ast.MeasurePrecondition):
            module = _observer(pre.observer, pre.loc, inst, host)
            inst.events[pre.observer.func] = PortRef(module, inst.modules[module].kind.event_ports[0])
            measuring.append(module)
    for exc in task.exceptions:
        module = _observer(exc.source, exc.loc, inst, host)
        inst.events[exc.name] = PortRef(module, inst.modules[module].kind.event_ports[0])
        if exc.adjust is not None:
            inst.adjustments[exc.name] = _adjustment(exc, inst)
    for post in task.postconditions:
        if isinstance(post, ast.MeasurePostcondition):
            module = _observer(post.observer, post.loc, inst, host)
            inst.events[post.observer.func] = PortRef(module, inst.modules[module].kind.event_ports[0])
    inst.measuring = tuple(measuring)


def _adjustment(exc: ast.ExceptionDecl, inst: RobotTaskInstance) -> Adjustment:
    """Check a type-1 update on throw-away instances: the parameters it sets and reads exist;
    a constant value (each end of a constant ramp) is valid for the parameter (type, range,
    finiteness); a computed one has the parameter's type at the nominal values (its range is
    checked when it is applied)."""
    adjust = exc.adjust
    assert adjust is not None, "a type-1 exception without its update was refused by the parser"
    target = adjust.target
    module = inst.modules.get(target.component)
    if module is None:
        raise OrccadError(_unknown_module(target.component, inst), target.loc)
    form = update_form(adjust.value)
    fresh = {name: spec.fresh(inst.context) for name, spec in inst.modules.items()}
    try:
        spec = fresh[target.component].param_spec(target.port)
    except OrccadError as error:
        raise _located(error, target.loc) from None

    if form.ramp is not None and spec.type not in ("float", "float|vector", "vector", "matrix"):
        raise OrccadError(f"a ramp moves a real parameter; {target.component}.{target.port} is "
                          f"a {spec.type}", adjust.value.loc)

    def read(name: str, param: str) -> Any:
        if name not in fresh:
            raise OrccadError(_unknown_module(name, inst))
        return fresh[name].get_param(param)

    values = []
    for expr in form.expressions:
        try:
            value = compute(expr, inst.params, read)
            values.append(value)
            _probe(fresh[target.component], spec, target.port, value, form.constant)
        except OrccadError as error:
            raise _located(error, getattr(expr, "loc", adjust.loc)) from None
    constant = values[0] if form.constant and form.ramp is None else None
    return Adjustment(exc.name, target.component, target.port, constant, form, adjust.loc)


def _unknown_module(name: str, inst: RobotTaskInstance) -> str:
    return (f"unknown module '{name}' in Robot-Task '{inst.task.name}' (its modules: "
            f"{', '.join(inst.modules)})")


def _probe(module: ModuleInstance, spec: Any, param: str, value: Any, constant: bool) -> None:
    """Set ``value`` on a throw-away ``module``: a constant must be valid; a value computed
    from the nominal parameters must have the parameter's type and shape (``kp`` a number or
    one per joint), its range being checked when the update is applied."""
    owner = module.kind.name
    if not constant:
        spec.convert(value, owner)
        try:
            spec.coerce(value, owner)
        except OrccadError:
            return  # out of range at the nominal values: checked when applied
    module.set_param(param, value)


def _priorities(modules: dict[str, ModuleSpec]) -> None:
    """Modules without a priority get rate-monotonic ones, below the explicit ones."""
    base = max((m.priority for m in modules.values()), default=0)
    pending = sorted((m for m in modules.values() if m.priority == 0),
                     key=lambda m: (m.timing.period_ns, m.name))
    for offset, module in enumerate(pending, start=1):
        module.priority = base + offset


def instantiate(task: ast.RobotTask, robots: Mapping[str, ast.Robot], host,
                args: tuple[ast.Arg, ...] = (), run_loc: SourceLocation | None = None,
                actual: Mapping[str, Any] | None = None) -> RobotTaskInstance:
    """Check ``task`` with the arguments of one ``run`` and build its instance; ``actual``
    gives the values of its run-time arguments (default: the nominal binding, see
    :func:`~orccad_app.robottask.values.task_arguments`)."""
    try:
        params = task_arguments(task, args, actual=actual)
    except OrccadError as error:
        raise _located(error, run_loc or task.loc) from None
    context = _context(task, params, robots, host)
    inst = RobotTaskInstance(task, params, task.robot, context, robots=robots, host=host,
                             args=args, run_loc=run_loc)
    inst.modules = _declared_modules(task, params, context, host)
    _law_defaults(inst, host)
    _conditions(inst, host)
    _priorities(inst.modules)
    robot = Endpoint.robot(task.robot, context.require_robot(f"Robot-Task '{task.name}'"))
    inst.connections = wire(task, inst.modules, robot)
    return inst


@dataclass(frozen=True)
class TaskInstances:
    """The checked instances of a program's Robot-Tasks.

    :param defaults: task name -> its instance with its default arguments (tasks that have
        them all).
    :param by_run: ``run`` statement location -> the instance of that run site (a run
        without arguments shares its task's default instance).
    """

    defaults: dict[str, RobotTaskInstance]
    by_run: dict[SourceLocation, RobotTaskInstance]


def _arguments_key(task: ast.RobotTask, args: tuple[ast.Arg, ...]) -> tuple | None:
    """``(task, bound parameter values)`` of a run, or ``None`` when they cannot be bound
    here (the instantiation reports why) or are not hashable."""
    try:
        values = task_arguments(task, args)
        key = (task.name, tuple((name, _frozen(value)) for name, value in sorted(values.items())))
        hash(key)
    except (OrccadError, TypeError):
        return None
    return key


def _frozen(value: Any) -> Any:
    """``value`` with its lists as tuples (vector arguments), to be a dictionary key."""
    if isinstance(value, list):
        return ("list", tuple(_frozen(item) for item in value))
    return value


def check_tasks(program: ast.Program, host) -> TaskInstances:
    """Instantiate every Robot-Task: once with its defaults (when it has them all) and once
    per ``run`` with that run's arguments (a run without arguments reuses the default
    instance, runs with equal argument values share one instance: 1000 runs of a task with 7
    different gains make 7 instances); raise on the first incoherence."""
    robots = {r.name: r for r in program.robots}
    tasks = {t.name: t for t in program.robottasks}
    defaults: dict[str, RobotTaskInstance] = {}
    by_run: dict[SourceLocation, RobotTaskInstance] = {}
    same: dict[tuple, RobotTaskInstance] = {}
    for declared in program.robottasks:
        if all(p.default is not None for p in declared.params):
            defaults[declared.name] = instantiate(declared, robots, host)
    for mission in program.missions + program.imported_missions:
        for run in runs(mission):
            task = tasks.get(run.task)
            if task is None:
                continue
            if not run.args and task.name in defaults:
                by_run[run.loc] = defaults[task.name]
                continue
            key = _arguments_key(task, run.args)
            if key is not None and key in same:
                by_run[run.loc] = same[key]  # the same arguments: the same instance
                continue
            try:
                by_run[run.loc] = instantiate(task, robots, host, run.args, run.loc)
                if key is not None:
                    same[key] = by_run[run.loc]
            except OrccadError as error:
                if not run.args or error.location == run.loc:
                    raise
                note = Diagnostic("note", "in this clause of the Robot-Task", error.location)
                raise OrccadError(f"{error.message} (with the arguments of this run of "
                                  f"{task.name})", run.loc, (note, *error.notes)) from None
    return TaskInstances(defaults, by_run)
