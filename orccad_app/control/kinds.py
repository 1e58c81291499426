"""Component kinds: named, parametrized factories that plugins register.

A kind pairs a name and declared :class:`~orccad_app.control.params.ParamSpec` s with a
factory. Three categories exist besides module kinds and robot types:

- :class:`TrajectoryKind` — ``create(params) -> Trajectory``
- :class:`TaskFunctionKind` — ``create(params, robot) -> TaskFunction``
- :class:`LawKind` — ``create(params, robot, task_function) -> ControlLaw``

``params`` may contain call forms for ``trajectory`` parameters when a ``resolver`` is
given (see :func:`orccad_app.control.spec.resolve`).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from orccad_app.control.params import ParamSpec, Resolver, resolve_params

if TYPE_CHECKING:
    from orccad_app.control.laws.base import ControlLaw
    from orccad_app.control.robot import RobotType
    from orccad_app.control.task_functions import TaskFunction
    from orccad_app.control.trajectories import Trajectory

__all__ = ["ComponentKind", "TrajectoryKind", "TaskFunctionKind", "LawKind", "DefaultModule",
           "STANDARD_SCHEME", "Spec"]


@dataclass(frozen=True)
class DefaultModule:
    """A Module-Task a law brings when the Robot-Task does not declare one of its ``kind``:
    ``name`` (made unique in the task) and the module kind, with the kind's default timing.
    Its inputs read the robot sensor or module output of the same name, and its outputs
    drive the robot actuator of the same name (``ctrl.tau -> arm.tau``)."""

    name: str
    kind: str


#: The scheme every law runs in unless it declares another one: a reference generator and
#: the ``control_law`` module running the law (``traj.qd -> ctrl.qd``, ``arm.q -> ctrl.q``,
#: ``ctrl.tau -> arm.tau``…).
STANDARD_SCHEME = (DefaultModule("traj", "trajectory"), DefaultModule("ctrl", "control_law"))


@dataclass(frozen=True)
class ComponentKind:
    """A named factory with declared parameters; ``summary`` is a one-line description."""

    name: str
    summary: str
    params: tuple[ParamSpec, ...]
    factory: Callable[..., Any]

    category = "component"

    def resolve_params(self, params: Mapping[str, Any],
                       resolver: Resolver | None = None) -> dict[str, Any]:
        """Validated parameter values (defaults filled in)."""
        return resolve_params(self.name, self.params, params, resolver)

    def param(self, name: str) -> ParamSpec:
        """The declared parameter ``name`` (``KeyError`` if absent)."""
        for spec in self.params:
            if spec.name == name:
                return spec
        raise KeyError(name)


@dataclass(frozen=True)
class TrajectoryKind(ComponentKind):
    """Factory of :class:`~orccad_app.control.trajectories.Trajectory` objects."""

    category = "trajectory"

    def create(self, params: Mapping[str, Any], resolver: Resolver | None = None) -> Trajectory:
        """A trajectory from user parameters; it remembers them (``origin``: this kind and
        the validated values) so that a type-1 update can rebuild it with one changed."""
        values = self.resolve_params(params, resolver)
        trajectory = self.factory(values)
        try:
            trajectory.origin = Spec(self, values)
        except AttributeError:  # a trajectory class with slots: not retunable
            pass
        return trajectory


@dataclass(frozen=True)
class TaskFunctionKind(ComponentKind):
    """Factory of :class:`~orccad_app.control.task_functions.TaskFunction` objects."""

    category = "task function"

    def create(self, params: Mapping[str, Any], robot: RobotType,
               resolver: Resolver | None = None) -> TaskFunction:
        """A task function for ``robot``; checks its dimension against the robot's."""
        return self.factory(self.resolve_params(params, resolver), robot)


@dataclass(frozen=True)
class LawKind(ComponentKind):
    """Factory of :class:`~orccad_app.control.laws.ControlLaw` objects."""

    category = "control law"

    #: The time-constrained specification's omitted parts: the Module-Tasks a Robot-Task
    #: with this ``law`` gets when it declares none of their kind.
    default_modules: tuple[DefaultModule, ...] = STANDARD_SCHEME

    def create(self, params: Mapping[str, Any], robot: RobotType,
               task_function: TaskFunction) -> ControlLaw:
        """A fresh law (its own integrator state) for ``robot`` and ``task_function``."""
        return self.factory(self.resolve_params(params), robot, task_function)


@dataclass(frozen=True)
class Spec:
    """A kind and its validated ``params``."""

    kind: ComponentKind
    params: Mapping[str, Any]

    @property
    def name(self) -> str:
        """The kind's name."""
        return self.kind.name

    def build(self, *deps: Any) -> Any:
        """A fresh object: ``kind.factory(params, *deps)`` (robot, task function…)."""
        return self.kind.factory(dict(self.params), *deps)
