"""Module kinds: the periodic Module-Tasks (MT) of a Robot-Task's time-constrained spec.

An MT follows RR-1801 §3.2::

    init; loop { read all input ports; compute; write all output ports }

A :class:`ModuleKind` (provided by a plugin, e.g. ``trajectory``, ``control_law``,
``joint_limits``) declares typed ports, parameters and a default :class:`Timing`;
:meth:`ModuleKind.create` makes a :class:`ModuleInstance` for one Robot-Task, given the
user's parameters and a :class:`ModuleContext` (the robot, the task function, the law).

Lifecycle of an instance, as the timed executive drives it (duck-typed):

- :meth:`ModuleInstance.init` — at each activation of the module (Robot-Task start,
  restart); resets internal state (integrators, filters, clocks).
- :meth:`ModuleInstance.compute` — once per job, with the values read from the input
  ports; returns the values to write on output ports. An ``event`` output is ``True`` in
  the jobs where the event fires and absent (or ``False``) otherwise.
- :meth:`ModuleInstance.set_param` — a type-1 exception (``adjust ctrl.kp = 200.0``)
  changes a parameter between two jobs; the value is validated like at creation.
  :meth:`ModuleInstance.get_param` reads its current value (``adjust ctrl.kp =
  min(ctrl.kp * 1.5, 800.0)``), :meth:`ModuleInstance.param_spec` its declaration.

Time given to ``compute`` is the executive clock ``t_s`` [s]; modules that need the time
since their own start (trajectories, integrators) measure it from their first job after
``init`` (see :meth:`ModuleInstance.task_time`).
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from collections.abc import Mapping
from typing import Any, ClassVar


from orccad_app.control.context import ModuleContext
from orccad_app.control.c_implementation import CImplementation
from orccad_app.control.errors import ControlError, InvalidParameter
from orccad_app.control.params import ParamSpec, close_matches, resolve_params
from orccad_app.control.ports import PORT_TYPES, PortDirection, PortSpec, Timing

__all__ = [
    "PORT_TYPES",
    "PortDirection",
    "PortSpec",
    "ParamSpec",
    "Timing",
    "ModuleContext",
    "ModuleKind",
    "ModuleInstance",
]

class ModuleKind(ABC):
    """A kind of Module-Task, registered by a plugin.

    Subclasses set the class attributes and implement :meth:`_instantiate`. A kind with
    at least one ``event`` output is an *observer*.
    """

    name: ClassVar[str]
    summary: ClassVar[str] = ""
    ports: ClassVar[tuple[PortSpec, ...]] = ()
    params: ClassVar[tuple[ParamSpec, ...]] = ()
    default_timing: ClassVar[Timing] = Timing(1_000_000, 100_000)
    #: Sets of input ports of which one must be connected in full for the module ever to
    #: compute (``tracking_error``: ``{e}`` or ``{q, qd}``). Empty: the required inputs,
    #: and for an observer whose inputs are all optional, any one of them.
    input_alternatives: ClassVar[tuple[frozenset[str], ...]] = ()
    #: The kind's C for ``orccad sil`` and ``orccad codegen --module-tasks``
    #: (:class:`~orccad_app.control.c_implementation.CImplementation`); ``None``: the kind
    #: exists only in Python and a mission running it in C is refused.
    c_implementation: ClassVar[CImplementation | None] = None

    @property
    def is_observer(self) -> bool:
        """True if the kind has an ``event`` output port."""
        return any(p.type == "event" and p.direction == "out" for p in self.ports)

    @property
    def event_ports(self) -> tuple[str, ...]:
        """Names of the ``event`` output ports."""
        return tuple(p.name for p in self.ports if p.type == "event" and p.direction == "out")

    def port(self, name: str) -> PortSpec:
        """The declared port ``name``; raises naming close matches."""
        for port in self.ports:
            if port.name == name:
                return port
        names = [p.name for p in self.ports]
        raise ControlError(f"module kind {self.name!r} has no port {name!r}"
                           f"{close_matches(name, names)}; its ports: {', '.join(names)}")

    def param(self, name: str) -> ParamSpec:
        """The parameter ``name``; raises naming close matches."""
        for spec in self.params:
            if spec.name == name:
                return spec
        names = [p.name for p in self.params]
        raise InvalidParameter(f"module kind {self.name!r} has no parameter {name!r}"
                               f"{close_matches(name, names)}; its parameters: "
                               f"{', '.join(names) or 'none'}")

    def sources(self, params: Mapping[str, Any]) -> dict[str, str]:
        """For each input port, the output port name it normally reads.

        A hint for the compiler when it instantiates an observer named in ``from`` without
        explicit ``connect``: wire ``ROBOT.<source>`` (a robot sensor) or the output of the
        same name of another module. The default maps each input to its own name.
        """
        return {p.name: p.name for p in self.ports if p.direction == "in"}

    def create(self, params: Mapping[str, Any], context: ModuleContext) -> ModuleInstance:
        """A new instance for one Robot-Task; validates ``params`` against :attr:`params`."""
        values = resolve_params(self.name, self.params, params)
        return self._instantiate(values, context)

    @abstractmethod
    def _instantiate(self, values: dict[str, Any], context: ModuleContext) -> ModuleInstance:
        """Build the instance from validated parameter values."""

    def __repr__(self) -> str:
        return f"<module kind {self.name}>"


class ModuleInstance(ABC):
    """One Module-Task of one Robot-Task: concrete ports, current parameters, state."""

    def __init__(self, kind: ModuleKind, params: dict[str, Any],
                 ports: tuple[PortSpec, ...]):
        self.kind = kind
        self.params = dict(params)
        self.ports = ports
        self._t0: float | None = None

    def port(self, name: str) -> PortSpec:
        """The concrete port ``name`` of this instance."""
        for port in self.ports:
            if port.name == name:
                return port
        return self.kind.port(name)

    def init(self) -> None:
        """Called when the module is activated, before its first job; resets its clock.

        Subclasses that keep state extend this (and call ``super().init()``).
        """
        self._t0 = None

    @abstractmethod
    def compute(self, t_s: float, inputs: Mapping[str, Any]) -> dict[str, Any]:
        """One job at executive time ``t_s`` [s]: inputs read → outputs to write.

        ``inputs`` maps input port names to values; an unconnected or never-written port
        is absent (or ``None``). Outputs not in the returned dict are not written.
        """

    def param_spec(self, name: str) -> ParamSpec:
        """The declaration of the settable parameter ``name``; raises naming the known ones.

        Subclasses whose instances have more settable parameters than their kind's (the
        control law's gains, a trajectory's parameters) extend it with :meth:`get_param`
        and :meth:`set_param`."""
        return self.kind.param(name)

    def get_param(self, name: str) -> Any:
        """The current value of parameter ``name`` (a type-1 update reads it)."""
        spec = self.param_spec(name)
        return self.params.get(name, spec.default)

    def set_param(self, name: str, value: Any) -> None:
        """Change parameter ``name`` (type-1 exception); validated like at creation."""
        spec = self.kind.param(name)
        self.params[name] = spec.coerce(value, f"{self.kind.name}")
        self._param_changed(name)

    def _param_changed(self, name: str) -> None:
        """Hook for subclasses that cache derived values of parameters."""

    def task_time(self, t_s: float) -> float:
        """Seconds since this instance's first job after :meth:`init` [s]."""
        if self._t0 is None:
            self._t0 = t_s
        return t_s - self._t0

    def __repr__(self) -> str:
        return f"<{self.kind.name} module {self.params}>"
