"""What a mission run steps: :class:`MissionReactor`, the interface of the Python
:class:`~orccad_app.reactive.runtime.Reactor` that :class:`~orccad_app.mission.run.MissionRun`
reads, so that another runtime of the plan's automaton can take its place (the controller
process's C automaton in ``orccad sil``, :mod:`orccad_app.sil.controller.automaton`)."""

from __future__ import annotations

from typing import Any, Protocol

from orccad_app.reactive.status import Status

__all__ = ["MissionReactor"]


class MissionReactor(Protocol):
    """What a run steps: :class:`~orccad_app.reactive.runtime.Reactor` (the Python runtime),
    or another runtime of the plan's automaton with its interface (the controller's C
    automaton in ``orccad sil``)."""

    state: int
    status: Status
    reason: str | None

    def step(self, inputs: Any = frozenset(), clock_ns: int | None = None) -> Any:
        """One instant: the step (``outputs``, ``valued``, ``status``, ``target``)."""

    def values(self, step: Any) -> dict[str, Any]:
        """The values of ``step``'s valued outputs."""

    @property
    def finished(self) -> bool:
        """The program has terminated."""

    @property
    def labels(self) -> frozenset:
        """The labels of the current state."""
