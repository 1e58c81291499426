"""Specs: a registered kind with validated parameters, resolved by name.

The plan language names components with arguments, nested for trajectories::

    task_function joint_tracking(trajectory = cosine(q0 = q0, omega = pi));
    law pid(kp = kp, kv = 40.0, ki = 10.0);

:func:`resolve` looks each name up in the plugin registries (unknown names raise
:class:`~orccad_app.diagnostics.OrccadError` listing close matches), validates the
arguments and builds nested trajectories. A :class:`Spec` builds a fresh object on each
:meth:`Spec.build`, so two modules never share an integrator.
:func:`module_context` assembles the :class:`~orccad_app.control.module.ModuleContext` of a
Robot-Task.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any, Protocol

from orccad_app.control.context import ModuleContext
from orccad_app.control.errors import ControlError
from orccad_app.control.kinds import Spec
from orccad_app.control.params import ParamSpec, as_call

__all__ = ["Spec", "KindLookup", "resolve", "module_context"]


class _Lookup(Protocol):
    def get(self, name: str) -> Any: ...


class KindLookup(Protocol):
    """What :func:`resolve` needs: one registry per category (see ``orccad_app.plugin_host``)."""

    robot_types: _Lookup
    control_laws: _Lookup
    task_functions: _Lookup
    trajectories: _Lookup


def _trajectory_resolver(registries: KindLookup):
    def resolve_trajectory(spec: ParamSpec, value: Any) -> Any:
        call = as_call(value)
        if call is None:
            return value
        name, args = call
        kind = registries.trajectories.get(name)
        return kind.create(args, resolver=resolve_trajectory)
    return resolve_trajectory


_CATEGORIES = {"control law": "control_laws", "task function": "task_functions",
               "trajectory": "trajectories"}


def resolve(registries: KindLookup, category: str, call: Any) -> Spec:
    """The :class:`Spec` of ``call`` (a call form, see :func:`~.params.as_call`) in
    ``category`` (``"control law"``, ``"task function"`` or ``"trajectory"``)."""
    if category not in _CATEGORIES:
        raise ControlError(f"unknown component category {category!r}")
    parsed = as_call(call)
    if parsed is None:
        raise ControlError(f"expected a {category} such as name(arg = value), got {call!r}")
    name, args = parsed
    kind = getattr(registries, _CATEGORIES[category]).get(name)
    params = kind.resolve_params(args, _trajectory_resolver(registries))
    return Spec(kind, params)


def module_context(registries: KindLookup, robot: str | Any | None = None,
                   task_function: Any = None, law: Any = None,
                   duration_s: float | None = None, robot_name: str | None = None,
                   robot_params: Mapping[str, Any] | None = None) -> ModuleContext:
    """A :class:`ModuleContext` from names, e.g.
    ``module_context(host, "arm3dof", ("joint_tracking", {"trajectory": ("cosine",
    {"q0": [0.5] * 3})}), ("pid", {"kp": 400.0}), duration_s=4.0, robot_name="arm")``.

    The task function and law are built once here to run their coherence checks
    (``dim e = dim q``, gains, shapes) before any module exists.
    """
    robot_type = registries.robot_types.get(robot) if isinstance(robot, str) else robot
    if robot_type is not None and robot_params:
        robot_type = robot_type.configure(robot_params)
    task_spec = None if task_function is None else resolve(registries, "task function",
                                                           task_function)
    law_spec = None if law is None else resolve(registries, "control law", law)
    if robot_type is not None and task_spec is not None:
        built = task_spec.build(robot_type)
        if law_spec is not None:
            law_spec.build(robot_type, built)
    elif law_spec is not None:
        raise ControlError(f"law {law_spec.name!r} needs a robot and a task function")
    return ModuleContext(robot=robot_type, task_function=task_spec, law=law_spec,
                         duration_s=duration_s, robot_name=robot_name)

