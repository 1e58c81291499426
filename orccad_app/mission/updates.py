"""Applying type-1 updates during a run (RR-1801 §3.4.2): computed values and ramps.

When the automaton emits ``X.E.adjust``, :meth:`TypeOneUpdates.apply` computes E's new value
in that instant from the *current* parameters of X's running Module-Tasks (``min(ctrl.kp *
1.5, 800.0)`` compounds on every repetition and stays under 800), sets it on the running module
and returns the :class:`~orccad_app.mission.result.UpdateRecord` (old and new value) that the
report and the trace log. A ramp ``ramp(START, END, D)`` sets ``START`` at once, then at every
release of the module within ``D`` the value interpolated at that instant, then ``END`` (a
sporadic module: every minimum inter-arrival time from the update); a new update of the same
parameter, or the end of the task's run, stops it.

A computed value is checked when it is applied, like a written one (type, declared range,
finiteness; for a ramp both ends): a bad value raises :class:`UpdateError`, which ends the run
``failed`` with the ``adjust`` clause's location, the instant and the value — never a clamp.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Callable

import numpy as np

from orccad_app.diagnostics import OrccadError
from orccad_app.executive.kernel import EventClass, Kernel
from orccad_app.mission.plan import ParamUpdate
from orccad_app.mission.result import RampRecord, UpdateRecord
from orccad_app.robottask.updates import compute
from orccad_app.tcs.graph import TCS
from orccad_app.tcs.module_task import ModuleTask
from orccad_app.tcs.phasing import Activation

__all__ = ["UpdateError", "TypeOneUpdates"]


class UpdateError(OrccadError):
    """A type-1 update computed a value its parameter refuses: the run ends ``failed``."""


@dataclass
class _Ramp:
    module: str
    param: str
    start: Any
    end: Any
    t0_ns: int
    duration_ns: int
    period_ns: int
    origin_ns: int
    """An instant of the module's release grid (its first release)."""
    entry: Any = None

    def value(self, t_ns: int) -> Any:
        fraction = min(1.0, (t_ns - self.t0_ns) / self.duration_ns)
        value = np.asarray(self.start) + (np.asarray(self.end) - np.asarray(self.start)) * fraction
        return float(value) if value.ndim == 0 else value


class TypeOneUpdates:
    """The type-1 updates of one run: see the module docstring.

    :param kernel: the run's kernel (clock, ramp steps).
    :param tcs: the mission's TCS (its Module-Tasks' current compute objects).
    :param on_param: the executive's ``on_param`` listeners (traces).
    """

    def __init__(self, kernel: Kernel, tcs: TCS,
                 on_param: list[Callable[..., None]]) -> None:
        self._kernel = kernel
        self._tcs = tcs
        self._on_param = on_param
        self._activated: dict[str, int] = {}
        self._ramps: dict[tuple[str, str], _Ramp] = {}

    def activated(self, modules: list[str], t_ns: int) -> None:
        """``modules`` were activated at ``t_ns``: their releases are at ``t_ns + k·T``."""
        for module in modules:
            self._activated[module] = t_ns

    def stop(self, modules: tuple[str, ...]) -> None:
        """The run of the task owning ``modules`` ended: its ramps stop."""
        for key in [k for k in self._ramps if k[0] in modules]:
            self._cancel(key)

    def apply(self, update: ParamUpdate, exception: str,
              at_ns: int | None = None) -> UpdateRecord:
        """Apply ``update`` (of type-1 exception ``exception``) now; the parameter write is
        stamped ``at_ns``, the instant of the reaction that raised the exception (default now:
        a reaction replayed later, in real time, stamps its write at its own instant)."""
        now = self._kernel.now
        stamp = now if at_ns is None else at_ns
        key = (update.module, update.param)
        self._cancel(key)
        old = self._compute(update.module).get_param(update.param)
        form = update.form
        if form is None or form.ramp is None:
            value = update.value if form is None or form.constant else \
                self._value(update, form.expressions[0], exception)
            self._set(update, value, exception, stamp)
            return UpdateRecord(update.module, update.param, old, value)
        start, end = (self._value(update, e, exception) for e in form.expressions)
        self._check(update, end, exception, "the end of its ramp")
        self._set(update, start, exception, stamp)
        task = self._task(update.module)
        periodic = task.activation is Activation.PERIODIC
        origin = self._activated.get(update.module, now) + task.offset_ns if periodic else now
        ramp = _Ramp(update.module, update.param, start, end, now, form.ramp.duration_ns,
                     task.period_ns, origin)
        self._ramps[key] = ramp
        self._schedule(ramp, update, exception)
        return UpdateRecord(update.module, update.param, old, start,
                            RampRecord(start, end, form.ramp.duration_ns))

    # -- internals ---------------------------------------------------------------------------

    def _task(self, module: str) -> ModuleTask:
        task = self._tcs.module(module)
        assert isinstance(task, ModuleTask)  # updates target Module-Tasks (checked at load)
        return task

    def _compute(self, module: str) -> Any:
        return self._task(module).compute

    def _value(self, update: ParamUpdate, expr: Any, exception: str) -> Any:
        def read(module: str, param: str) -> Any:
            return self._compute(update.modules[module]).get_param(param)
        try:
            return compute(expr, update.env, read)
        except OrccadError as error:
            raise self._error(update, exception, error.message) from None

    def _check(self, update: ParamUpdate, value: Any, exception: str, what: str) -> None:
        compute_object = self._compute(update.module)
        try:
            compute_object.param_spec(update.param).coerce(value, compute_object.kind.name)
        except OrccadError as error:
            raise self._error(update, exception, f"{what}: {error.message}") from None

    def _set(self, update: ParamUpdate, value: Any, exception: str,
             at_ns: int | None = None) -> None:
        try:
            self._compute(update.module).set_param(update.param, value)
        except Exception as error:  # a refused value, or a module's own failure
            message = error.message if isinstance(error, OrccadError) else \
                f"{type(error).__name__}: {error}"
            raise self._error(update, exception, message) from None
        stamp = self._kernel.now if at_ns is None else at_ns
        for hook in self._on_param:
            hook(stamp, update.module, update.param, value)

    def _error(self, update: ParamUpdate, exception: str, message: str) -> UpdateError:
        where = f"{update.loc}: " if update.loc is not None else ""
        return UpdateError(f"{where}type-1 update of {update.module}.{update.param} by "
                           f"{exception} at t = {self._kernel.now / 1e9:g} s: {message}",
                           update.loc)

    def _schedule(self, ramp: _Ramp, update: ParamUpdate, exception: str) -> None:
        """The ramp's next step: the module's next release after now (or its end)."""
        now = self._kernel.now
        origin = ramp.origin_ns
        step = origin + ((now - origin) // ramp.period_ns + 1) * ramp.period_ns
        step = min(step, ramp.t0_ns + ramp.duration_ns)
        ramp.entry = self._kernel.schedule(step, EventClass.CONTROL, self._step,
                                           (ramp, update, exception))

    def _step(self, payload: tuple[_Ramp, ParamUpdate, str]) -> None:
        ramp, update, exception = payload
        now = self._kernel.now
        value = ramp.value(now)
        done = now >= ramp.t0_ns + ramp.duration_ns
        if done:
            del self._ramps[(ramp.module, ramp.param)]
            self._set(update, value, exception)  # the end value, logged
            return
        try:  # the steps between the logged start and end are not traced
            self._compute(ramp.module).set_param(ramp.param, value)
        except Exception as error:
            message = error.message if isinstance(error, OrccadError) else str(error)
            raise self._error(update, exception, message) from None
        self._schedule(ramp, update, exception)

    def _cancel(self, key: tuple[str, str]) -> None:
        ramp = self._ramps.pop(key, None)
        if ramp is not None and ramp.entry is not None:
            self._kernel.cancel(ramp.entry)
