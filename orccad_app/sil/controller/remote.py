"""A Module-Task whose compute runs in the controller process: :class:`RemoteModule`, and
the run site that starts them (:class:`RemoteSite`).

The executive drives a :class:`RemoteModule` as it drives a Python module instance (``init``,
``compute``, ``set_param``, ``get_param``, ``param_spec``), but each call becomes a request
to the controller process (:class:`~orccad_app.sil.controller.process.ControllerProcess`), where the
C Module-Task keeps all the state that ``compute`` uses. The Python instance made for the same
start (its *shadow*) never computes: it validates type-1 updates and gives the parameter
vector of the C layout (:func:`~orccad_app.sil.generate.layout.c_layout`), so a run-time argument or an
update reaches the C Module-Task exactly as the Python one would have taken it.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from typing import Any

import numpy as np

from orccad_app.mission.plan import MissionPlan, SiteModules
from orccad_app.reactive.automaton import Automaton
from orccad_app.sil.controller.process import ControllerFailure, ControllerProcess, Op
from orccad_app.sil.generate.layout import CLayout, c_layout, same_word
from orccad_app.sil.generate.table import ModuleTable

__all__ = ["ControllerRun", "RemoteModule", "RemoteSite", "remote_plan"]


class RemoteModule:
    """The proxy of table entry ``index`` (see the module docstring).

    :param controller: the controller process.
    :param index: the Module-Task's index in the generated table.
    :param nominal: its layout in the table (the parameters compiled in).
    :param shadow: the Python instance of this start (never computes).
    :param start: send the fresh start (``START``, then the run-time arguments); ``False``
        when the controller has started it itself (its real-time automaton task).
    :param c_owned: the parameter words the controller's automaton task alone writes (its
        type-1 updates, :mod:`orccad_app.sil.generate.adjust`): never sent.
    :param c_bound: the parameter words the automaton task binds to the run-time arguments
        when it starts the Module-Task itself (:mod:`orccad_app.sil.generate.binds`).
    """

    def __init__(self, controller: ControllerProcess, index: int, nominal: CLayout,
                 shadow: Any, start: bool = True, c_owned: frozenset[int] = frozenset(),
                 c_bound: frozenset[int] = frozenset()) -> None:
        self._controller = controller
        self._index = index
        self._shadow = shadow
        self.kind = shadow.kind
        self.ports = shadow.ports
        layout = c_layout(shadow)
        if layout.kind != nominal.kind or layout.inputs != nominal.inputs \
                or layout.outputs != nominal.outputs:
            raise ControllerFailure(f"module-task {index}: this start's layout differs from "
                                    f"the generated table's")
        self._layout = layout
        self._inputs = [(p.name, p.dim) for p in layout.inputs]
        self._outputs = [(p.name, p.type, p.dim) for p in layout.outputs]
        self._retired = False
        self._c_owned = c_owned
        if not start:
            if any(not same_word(old, new) and at not in c_bound
                   for at, (old, new) in enumerate(zip(nominal.params, layout.params))):
                raise ControllerFailure(f"module-task {index}: started by the controller with "
                                        f"its nominal parameters and the run-time arguments "
                                        f"it binds, but this start binds others")
            return
        controller.request(Op.START, index)
        if layout.params != nominal.params:  # run-time arguments bound at this start
            self._send_params(layout.params)

    def retire(self) -> None:
        """The controller has started this Module-Task afresh: this proxy's run is over, its
        parameter writes stay with its shadow."""
        self._retired = True

    @property
    def params(self) -> dict[str, Any]:
        """The current parameters (the shadow's: updated with every type-1 update)."""
        return self._shadow.params

    def _send_params(self, params: tuple[float, ...]) -> None:
        if not self._retired:
            self._controller.request(Op.PARAM, self._index, values=list(params), offset=0)
            self._controller.supervisor_writes += len(params)

    def _send_changes(self, old: tuple[float, ...], new: tuple[float, ...]) -> None:
        """The words that changed, each run of them one ``PARAM`` request, but those the
        controller writes itself."""
        at, size = 0, len(new)
        while at < size and not self._retired:
            if at in self._c_owned or same_word(old[at], new[at]):
                at += 1
                continue
            end = at
            while end < size and end not in self._c_owned and not same_word(old[end], new[end]):
                end += 1
            self._controller.request(Op.PARAM, self._index, values=list(new[at:end]),
                                     offset=at)
            self._controller.supervisor_writes += end - at
            at = end

    def init(self) -> None:
        """Activation: the C Module-Task resets its state."""
        self._controller.request(Op.INIT, self._index)

    def compute(self, t_s: float, inputs: Mapping[str, Any]) -> dict[str, Any]:
        """One job, computed by the controller process."""
        values: list[float] = []
        for name, dim in self._inputs:
            value = inputs.get(name)
            if value is None:
                values.extend([0.0] * (dim + 1))
                continue
            array = np.asarray(value, dtype=float).reshape(-1)
            if array.size != dim:
                raise ControllerFailure(f"input {name!r} has {array.size} components, the C "
                                        f"Module-Task expects {dim}")
            values.append(1.0)
            values.extend(array.tolist())
        reply = self._controller.request(Op.COMPUTE, self._index, t_s, values)
        outputs: dict[str, Any] = {}
        at = 0
        for name, kind, dim in self._outputs:
            present = reply[at] != 0.0
            data = reply[at + 1:at + 1 + dim]
            at += 1 + dim
            if not present:
                continue
            if kind == "vector":
                outputs[name] = np.array(data)
            elif kind == "bool":
                outputs[name] = data[0] != 0.0
            elif kind == "event":
                outputs[name] = True
            else:
                outputs[name] = data[0]
        return outputs

    def param_spec(self, name: str) -> Any:
        """The declaration of parameter ``name`` (the shadow's)."""
        return self._shadow.param_spec(name)

    def get_param(self, name: str) -> Any:
        """The current value of parameter ``name``."""
        return self._shadow.get_param(name)

    def set_param(self, name: str, value: Any) -> None:
        """A type-1 update: validated by the shadow, then the parameter words it changed sent
        (but those the controller writes itself)."""
        self._shadow.set_param(name, value)
        layout = c_layout(self._shadow)
        self._send_changes(self._layout.params, layout.params)
        self._layout = layout

    def __repr__(self) -> str:
        return f"<{self.kind.name} module in the controller process, entry {self._index}>"


@dataclasses.dataclass
class RemoteSite(SiteModules):
    """A run site whose starts make proxies to the controller process."""

    controller: Any = None
    table: Any = None
    managed: bool = False
    """The controller starts its Module-Tasks itself (its real-time automaton task)."""
    c_owned: Mapping[str, frozenset[int]] = dataclasses.field(default_factory=dict)
    """Per Module-Task, the parameter words the automaton task alone writes (its type-1
    updates): the proxies never send them."""
    c_bound: Mapping[str, frozenset[int]] = dataclasses.field(default_factory=dict)
    """Per Module-Task, the parameter words the automaton task binds to the run-time
    arguments at a start."""

    def fresh_computes(self, instance: Any = None) -> dict[str, Any]:
        shadows = super().fresh_computes(instance)
        table: ModuleTable = self.table
        proxies = {}
        for name, shadow in shadows.items():
            index = table.index(name)
            proxies[name] = RemoteModule(self.controller, index, table.entries[index].layout,
                                         shadow, start=not self.managed,
                                         c_owned=self.c_owned.get(name, frozenset()),
                                         c_bound=self.c_bound.get(name, frozenset()))
        return proxies


@dataclasses.dataclass(frozen=True)
class ControllerRun:
    """A started controller and the plan a run of it runs.

    :param controller: the controller process.
    :param table: its generated table.
    :param plan: a copy of the mission's plan (:func:`remote_plan`): the full automaton, run
        sites whose starts make :class:`RemoteModule` proxies.
    """

    controller: ControllerProcess
    table: ModuleTable
    plan: MissionPlan


def remote_plan(plan: MissionPlan, automaton: Automaton, table: ModuleTable,
                controller: ControllerProcess, managed: frozenset[int] = frozenset(),
                c_owned: Mapping[str, frozenset[int]] | None = None,
                c_bound: Mapping[str, frozenset[int]] | None = None) -> MissionPlan:
    """A copy of ``plan`` (``plan`` itself unchanged) whose automaton is the full
    ``automaton`` the controller runs and whose run sites start their Module-Tasks in
    ``controller``; the sites numbered in ``managed`` are started by the controller itself,
    the parameter words ``c_owned`` of their Module-Tasks written by it alone, ``c_bound``
    bound by it to the run-time arguments."""
    sites: list[SiteModules] = []
    for site in plan.sites:
        fields = {f.name: getattr(site, f.name) for f in dataclasses.fields(SiteModules)}
        own = site.number in managed
        sites.append(RemoteSite(**fields, controller=controller, table=table, managed=own,
                                c_owned=(c_owned or {}) if own else {},
                                c_bound=(c_bound or {}) if own else {}))
    return dataclasses.replace(plan, automaton=automaton, sites=sites)
