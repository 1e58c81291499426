"""The ``trajectory`` and ``control_law`` module kinds of a Robot-Task.

Both read the Robot-Task's task function and law from the :class:`ModuleContext`.
Reference ports are named after the task function's reference (``qd`` for joint tracking,
``xd`` for Cartesian tracking): ``qd`` [rad], ``qd_dot`` [rad/s], ``qd_ddot`` [rad/s²].

``trajectory`` (default 2 ms period, 0.3 ms WCET)
    out ``qd``, ``qd_dot``, ``qd_ddot``; in ``q`` (optional: the start of a trajectory
    given without one, e.g. ``min_jerk(goal = …, duration = 2.0)``).
``control_law`` (default 1 ms period, 0.5 ms WCET)
    in ``qd`` and ``q`` (required), ``qd_dot``, ``qd_ddot``, ``qdot`` (optional:
    when unconnected, ``qd_dot`` and ``qdot`` are estimated by backward differences and
    ``qd_ddot`` from successive ``qd_dot``); out ``tau`` [N·m] (after the actuator
    constraint), ``e`` (the task error) and ``saturated`` (a joint at a torque bound).
    Parameters are the law's (``module ctrl : control_law(kp = 300.0)`` overrides the
    Robot-Task's ``law``); ``set_param("kp", 200.0)`` updates it between jobs.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from orccad_app.control.errors import ControlError, DimensionMismatch, InvalidParameter
from orccad_app.control.kinds import Spec
from orccad_app.control.estimation import BackwardDifference
from orccad_app.control.laws.base import ControlLaw
from orccad_app.control.module import ModuleContext, ModuleInstance, ModuleKind, PortSpec, Timing
from orccad_app.control.params import ParamSpec, close_matches
from orccad_app.control.ports import TASK_ERROR
from orccad_app.control.task_functions import TaskFunction
from orccad_app.control.trajectories import Sample, retune

__all__ = ["TrajectoryModule", "ControlLawModule"]


def _reference_ports(ref: str, direction: str, required: bool) -> tuple[PortSpec, ...]:
    return (PortSpec(ref, direction, "vector", None, True, "reference position"),
            PortSpec(f"{ref}_dot", direction, "vector", None, required, "reference velocity"),
            PortSpec(f"{ref}_ddot", direction, "vector", None, required,
                     "reference acceleration"))


def _task_function(who: str, context: ModuleContext) -> TaskFunction:
    robot = context.require_robot(who)
    if context.task_function is None:
        raise ControlError(f"{who} needs the Robot-Task's task_function")
    return context.task_function.build(robot)


def _concrete(ports: tuple[PortSpec, ...], ref: str, ref_dim: int,
              dof: int) -> tuple[PortSpec, ...]:
    """Ports with the reference renamed (``qd`` → ``ref``) and dims fixed: reference ports
    and ``e`` have the task dimension, other vectors the robot's number of joints."""
    concrete = []
    reference = {"qd": ref, "qd_dot": f"{ref}_dot", "qd_ddot": f"{ref}_ddot"}
    for port in ports:
        is_task = port.name in reference or port.name == TASK_ERROR
        name = reference.get(port.name, port.name)
        spec = PortSpec(name, port.direction, port.type, None, port.required, port.doc)
        concrete.append(spec.with_dim(ref_dim if is_task else dof))
    return tuple(concrete)


class TrajectoryModule(ModuleKind):
    """Samples the task function's trajectory at each job (time from its first job)."""

    name = "trajectory"
    summary = "samples the Robot-Task's reference trajectory"
    ports = _reference_ports("qd", "out", True) + (
        PortSpec("q", "in", "vector", None, False, "measured joints, for a missing start"),)
    params = ()
    default_timing = Timing.from_ms(2.0, 0.3)

    def _instantiate(self, values: dict[str, Any], context: ModuleContext) -> ModuleInstance:
        return _TrajectoryInstance(self, values, context)


class _TrajectoryInstance(ModuleInstance):
    def __init__(self, kind: ModuleKind, values: dict[str, Any], context: ModuleContext):
        self._context = context
        self.task_function = _task_function(kind.name, context)
        self._origin = self.task_function.trajectory.origin
        self._start: np.ndarray | None = None
        self._last_t_s: float | None = None  # task time of the last job [s]
        self.ref = self.task_function.reference_name
        self._ref_dot, self._ref_ddot = f"{self.ref}_dot", f"{self.ref}_ddot"
        ports = _concrete(kind.ports, self.ref, self.task_function.dim, self.task_function.dof)
        super().__init__(kind, values, ports)

    def init(self) -> None:
        super().init()
        self.task_function = _task_function(self.kind.name, self._context)
        self._origin = self.task_function.trajectory.origin
        self._start = None
        self._last_t_s = None

    def param_spec(self, name: str) -> ParamSpec:
        """The trajectory's parameters (``traj.omega`` of ``cosine``) are the module's."""
        origin = self._origin
        specs = {} if origin is None else {s.name: s for s in origin.kind.params
                                           if s.type != "trajectory"}
        if name not in specs:
            what = "a trajectory without parameters" if origin is None else \
                f"trajectory {origin.name!r}"
            raise InvalidParameter(f"module kind 'trajectory' ({what}) has no parameter "
                                   f"{name!r}{close_matches(name, list(specs))}; its "
                                   f"parameters: {', '.join(specs) or 'none'}")
        return specs[name]

    def get_param(self, name: str) -> Any:
        self.param_spec(name)
        return self._origin.params[name]

    def set_param(self, name: str, value: Any) -> None:
        """Rebuild the trajectory with ``name`` changed (validated); its time goes on from the
        module's start, a measured start position is kept, and the set-point stays continuous
        from the last job on (:mod:`orccad_app.control.trajectories.retuned`)."""
        self.param_spec(name)
        origin = self._origin
        trajectory = origin.kind.create({**origin.params, name: value})
        if not trajectory.needs_start and trajectory.dim != self.task_function.dim:
            raise DimensionMismatch(f"trajectory {origin.name!r}: {name} gives "
                                    f"{trajectory.dim} components, the task has "
                                    f"{self.task_function.dim}")
        previous = self.task_function.trajectory
        self.task_function.trajectory = trajectory
        if self._start is not None:
            self.task_function.start_from(self._start)
        if self._last_t_s is not None and not previous.needs_start:
            # the set-point stays continuous (phase, then a C² blend: trajectories/retuned.py)
            self.task_function.trajectory = retune(previous, self.task_function.trajectory,
                                                   self._last_t_s)
        self._origin = trajectory.origin

    def compute(self, t_s: float, inputs: Mapping[str, Any]) -> dict[str, Any]:
        if self.task_function.trajectory.needs_start:
            q = inputs.get("q")
            if q is None:
                return {}
            self._start = np.asarray(q, dtype=float)
            self.task_function.start_from(self._start)
        self._last_t_s = self.task_time(t_s)
        sample = self.task_function.reference(self._last_t_s)
        return {self.ref: sample.pos, self._ref_dot: sample.vel, self._ref_ddot: sample.acc}


class ControlLawModule(ModuleKind):
    """Runs the Robot-Task's control law: reference and joint state in, torque out."""

    name = "control_law"
    summary = "the Robot-Task's control law (eq. 5 family) and actuator constraint"
    ports = _reference_ports("qd", "in", False) + (
        PortSpec("q", "in", "vector", None, True, "joint positions [rad]"),
        PortSpec("qdot", "in", "vector", None, False, "joint velocities [rad/s]"),
        PortSpec("tau", "out", "vector", None, True, "joint torques [N·m]"),
        PortSpec(TASK_ERROR, "out", "vector", None, True, "task error e(q, t)"),
        PortSpec("saturated", "out", "bool", None, True, "a torque is at its bound"),
    )
    params: tuple[ParamSpec, ...] = ()
    default_timing = Timing.from_ms(1.0, 0.5)

    def create(self, params: Mapping[str, Any], context: ModuleContext) -> ModuleInstance:
        """An instance whose law is the Robot-Task's, with ``params`` overriding its gains."""
        if context.law is None:
            raise ControlError("control_law needs the Robot-Task's law")
        return _ControlLawInstance(self, dict(params), context)

    def _instantiate(self, values: dict[str, Any], context: ModuleContext) -> ModuleInstance:
        return _ControlLawInstance(self, values, context)


class _ControlLawInstance(ModuleInstance):
    def __init__(self, kind: ModuleKind, overrides: dict[str, Any], context: ModuleContext):
        self._context = context
        self._overrides = overrides
        self.law = self._build_law()
        self._task_function_spec: Spec = context.task_function  # type: ignore[assignment]
        self.ref = self.law.task_function.reference_name
        self._ref_dot, self._ref_ddot = f"{self.ref}_dot", f"{self.ref}_ddot"
        ports = _concrete(kind.ports, self.ref, self.law.task_function.dim, self.law.robot.dof)
        super().__init__(kind, dict(self.law.params), ports)
        self._velocity = BackwardDifference()
        self._ref_velocity = BackwardDifference(on_change=True)
        self._ref_acceleration = BackwardDifference(on_change=True)

    def _build_law(self) -> ControlLaw:
        task_function = _task_function("control_law", self._context)
        spec = self._context.law
        return spec.kind.create({**spec.params, **self._overrides}, self._context.robot,
                                task_function)

    def init(self) -> None:
        super().init()
        self.law.reset()
        for estimator in (self._velocity, self._ref_velocity, self._ref_acceleration):
            estimator.reset()

    def _task_function_params(self) -> dict[str, ParamSpec]:
        spec = self._context.task_function
        return {} if spec is None else {s.name: s for s in spec.kind.params
                                        if s.type != "trajectory"}

    def param_spec(self, name: str) -> ParamSpec:
        """The law's parameters (``kp``…), then the task function's (``damping``…)."""
        law = {spec.name: spec for spec in self.law.PARAMS}
        found = law.get(name) or self._task_function_params().get(name)
        if found is None:
            known = [*law, *self._task_function_params()]
            raise InvalidParameter(f"module 'control_law' (law {self.law.name!r}) has no "
                                   f"parameter {name!r}{close_matches(name, known)}; its "
                                   f"parameters: {', '.join(known)}")
        return found

    def get_param(self, name: str) -> Any:
        spec = self.param_spec(name)
        if name in self.law.params:
            return self.law.params[name]
        return self._task_function_spec.params.get(name, spec.default)

    def set_param(self, name: str, value: Any) -> None:
        """Retune the law (type-1 exception), validated against the law's parameters; or
        rebuild its task function with one of its parameters changed (``damping``)."""
        self.param_spec(name)
        if any(spec.name == name for spec in self.law.PARAMS):
            self.law.set_param(name, value)
            self.params = dict(self.law.params)
            return
        spec = self._task_function_spec
        values = spec.kind.resolve_params({**spec.params, name: value})
        self.law.task_function = spec.kind.factory(values, self.law.robot)
        self.law._prepare()
        self._task_function_spec = Spec(spec.kind, values)

    def _reference(self, t_s: float, inputs: Mapping[str, Any]) -> Sample | None:
        pos = inputs.get(self.ref)
        if pos is None:
            return None
        pos = np.asarray(pos, dtype=float)
        vel = inputs.get(self._ref_dot)
        vel = self._ref_velocity.update(t_s, pos) if vel is None else np.asarray(vel, float)
        acc = inputs.get(self._ref_ddot)
        if acc is None:
            acc = self._ref_acceleration.update(t_s, vel)
        return Sample(pos=pos, vel=vel, acc=np.asarray(acc, dtype=float))

    def compute(self, t_s: float, inputs: Mapping[str, Any]) -> dict[str, Any]:
        reference = self._reference(t_s, inputs)
        q = inputs.get("q")
        if reference is None or q is None:
            return {}
        q = np.asarray(q, dtype=float)
        qdot = inputs.get("qdot")
        qdot = self._velocity.update(t_s, q) if qdot is None else np.asarray(qdot, float)
        out = self.law.command(t_s, q, qdot, reference)
        return {"tau": out.tau, TASK_ERROR: out.e, "saturated": True in out.saturated.tolist()}

