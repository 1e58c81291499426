"""The observer base: a module kind whose instances emit an event when a condition holds.

Every observer has the output ports ``event`` (type ``event``: present in the jobs where
it fires) and ``value`` (``float``: the monitored quantity, for traces), the parameter
``edge`` and the default timing 5 ms period, 0.1 ms WCET.

``edge = false`` (default): the event fires in every job where the condition holds, which
is what measurement pre/post-conditions need ("holds now"). ``edge = true``: only in the
job where the condition becomes true.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from collections.abc import Mapping
from typing import Any, ClassVar

from orccad_app.plugin_api import (
    ModuleContext,
    ModuleInstance,
    ModuleKind,
    ParamSpec,
    PortSpec,
    Timing,
)

__all__ = ["Monitor", "ObserverKind", "ObserverInstance", "EVENT_PORT", "VALUE_PORT"]

EVENT_PORT = PortSpec("event", "out", "event", doc="fires while (or when) the condition holds")
VALUE_PORT = PortSpec("value", "out", "float", doc="the monitored quantity")
EDGE_PARAM = ParamSpec("edge", "bool", False, "fire only when the condition becomes true")


class Monitor(ABC):
    """The per-instance condition of an observer; reads current parameters in ``params``."""

    def __init__(self, params: Mapping[str, Any], context: ModuleContext):
        self.params = params
        self.context = context

    def reset(self) -> None:
        """Forget state at activation (override when the monitor keeps some)."""

    @abstractmethod
    def __call__(self, t_s: float, inputs: Mapping[str, Any]) -> tuple[bool, float] | None:
        """``(condition holds, monitored value)`` at task time ``t_s`` [s], or ``None``
        when the needed inputs have no value yet."""


class ObserverKind(ModuleKind):
    """An observer: declare :attr:`inputs`, :attr:`own_params` and :attr:`monitor`."""

    inputs: ClassVar[tuple[PortSpec, ...]] = ()
    own_params: ClassVar[tuple[ParamSpec, ...]] = ()
    monitor: ClassVar[type[Monitor]]
    default_timing = Timing.from_ms(5.0, 0.1)

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        cls.ports = cls.inputs + (EVENT_PORT, VALUE_PORT)
        cls.params = cls.own_params + (EDGE_PARAM,)

    def input_dims(self, values: Mapping[str, Any], context: ModuleContext) -> dict[str, int]:
        """Concrete dims of vector inputs; by default the robot's number of joints."""
        if context.robot is None:
            return {}
        return {port.name: context.robot.dof for port in self.inputs if port.type == "vector"}

    def _instantiate(self, values: dict[str, Any], context: ModuleContext) -> ModuleInstance:
        self.check(values, context)
        dims = self.input_dims(values, context)
        ports = tuple(port.with_dim(dims.get(port.name)) for port in self.ports)
        instance = ObserverInstance(self, values, ports)
        instance.monitor = self.monitor(instance.params, context)
        instance.init()
        return instance

    def check(self, values: Mapping[str, Any], context: ModuleContext) -> None:
        """Coherence checks against the robot and task (raise naming the bad value)."""


class ObserverInstance(ModuleInstance):
    """Runs the kind's :class:`Monitor` each job; see the module docstring."""

    monitor: Monitor

    def init(self) -> None:
        super().init()
        self._held = False
        self.monitor.reset()

    def compute(self, t_s: float, inputs: Mapping[str, Any]) -> dict[str, Any]:
        result = self.monitor(self.task_time(t_s), inputs)
        if result is None:
            return {}
        holds, value = result
        fires = holds and not (self.params["edge"] and self._held)
        self._held = holds
        outputs: dict[str, Any] = {"value": float(value)}
        if fires:
            outputs["event"] = True
        return outputs

    def set_param(self, name: str, value: Any) -> None:
        """Change a parameter; the monitor sees the new value at the next job."""
        super().set_param(name, value)
        self.monitor.params = self.params
