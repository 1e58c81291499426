"""A counterexample replayed instant by instant, as a mission designer reads it.

:func:`replay` runs a failed property's :class:`~orccad_app.verify.counterexample.Script` on
the composed automaton it was found on (the same :class:`~orccad_app.reactive.runtime.Reactor`
``orccad react --composed`` uses) and keeps, for each instant, what a designer asks: which
inputs were present, what the mission emitted, and **where it waits** afterwards — the source
statements of the automaton's state (``false_property.orc:40``), the Robot-Tasks active in it
— with the instant where the property fails marked (the last one of a finite counterexample;
for a run that loops forever, the first instant of the loop).

:func:`script_instants` gives the script's instants as ``orccad react`` scripts hold them, for
a run against the plant (:func:`orccad_app.mission.scripted.script_injections`).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

from orccad_app.diagnostics import OrccadError, SourceLocation
from orccad_app.reactive.automaton import Automaton
from orccad_app.reactive.labels import InMission, MissionLabel
from orccad_app.reactive.runtime import Reactor
from orccad_app.reactive.script import Instant
from orccad_app.reactive.status import Status
from orccad_app.robottask.composition import Composition
from orccad_app.robottask.labels import RtLabel
from orccad_app.verify.checker import PropertyOutcome
from orccad_app.verify.counterexample import Script

__all__ = ["waiting_at", "RunningTask", "ReplayStep", "Replay", "replay", "script_instants", "step_lines", "format_replay",
           "FAILS", "LOOPS"]

FAILS = "the property fails at this instant"
"""The mark of the last instant of a finite counterexample."""
LOOPS = "from this instant on, the run repeats forever and the property never holds"
"""The mark of the first instant of a counterexample's loop."""


def waiting_at(automaton: Automaton, state: int) -> tuple[SourceLocation, ...]:
    """Where ``state`` of ``automaton`` waits: the statements it is paused at, then the
    ``run mission`` statements of the sub-missions it is inside (a statement of an imported
    file is reached from the mission's own file through them); unique, in that order."""
    found: list[SourceLocation] = []
    if 0 <= state < len(automaton.waiting):
        found += automaton.waiting[state]
    labels = automaton.labels[state] if automaton.labels and 0 <= state < len(
        automaton.labels) else ()
    found += sorted((label.call for label in labels
                     if isinstance(label, MissionLabel) and label.call.line > 0),
                    key=lambda loc: (loc.file, loc.line))
    return tuple(dict.fromkeys(found))


@dataclass(frozen=True)
class RunningTask:
    """A Robot-Task active in a state, and its ``run`` statement."""

    task: str
    site: int
    loc: SourceLocation


@dataclass(frozen=True)
class ReplayStep:
    """One instant of a replayed counterexample.

    :param number: the instant, from 1 (the script's line order).
    :param time_ns: the instant's clock [ns] when the script times it, else ``None``.
    :param inputs: the inputs present, with their values (``None`` for a pure signal).
    :param outputs: what the automaton emitted.
    :param state: the automaton's state after the reaction.
    :param status: the mission's status after it (``running``, ``done``…).
    :param waiting: the statements the new state waits at.
    :param tasks: the Robot-Tasks active in the new state, with their ``run`` statements.
    :param mark: :data:`FAILS`, :data:`LOOPS` or ``""``.
    :param inside: the sub-mission instances (``run mission``) the new state is in.
    """

    number: int
    time_ns: int | None
    inputs: tuple[tuple[str, Any], ...]
    outputs: tuple[str, ...]
    state: int
    status: str
    waiting: tuple[SourceLocation, ...]
    tasks: tuple[RunningTask, ...]
    mark: str = ""
    inside: tuple[InMission, ...] = ()

    def lines_in(self, path: str) -> list[int]:
        """The lines of file ``path`` the state waits at (sorted, unique)."""
        name = Path(path).name
        return sorted({loc.line for loc in self.waiting
                       if loc.line > 0 and Path(loc.file or name).name == name})

    def run_lines_in(self, path: str) -> list[int]:
        """The lines of file ``path`` of the running tasks' ``run`` statements."""
        name = Path(path).name
        return sorted({task.loc.line for task in self.tasks
                       if task.loc.line > 0 and Path(task.loc.file or name).name == name})


@dataclass(frozen=True)
class Replay:
    """A failed property's counterexample, replayed (see the module docstring)."""

    mission: str
    kind: str
    name: str
    message: str
    steps: tuple[ReplayStep, ...]
    loop_start: int | None
    """Index in ``steps`` of the loop's first instant (``None``: a finite counterexample)."""
    note: str = ""

    @property
    def failing(self) -> int:
        """Index in ``steps`` of the marked instant."""
        return next((i for i, step in enumerate(self.steps) if step.mark), len(self.steps) - 1)

    @property
    def title(self) -> str:
        return f"counterexample to {self.kind} {self.mission}.{self.name}: {self.message}"


def _tasks(composition: Composition, state: int) -> tuple[RunningTask, ...]:
    automaton: Automaton = composition.automaton
    labels = automaton.labels[state] if automaton.labels and state < len(automaton.labels) \
        else ()
    numbers = {label.site for label in labels if isinstance(label, RtLabel)}
    return tuple(RunningTask(site.robottask.name, site.number, site.stmt.loc)
                 for site in composition.sites if site.number in numbers)


def replay(composition: Composition, outcome: PropertyOutcome) -> Replay:
    """Replay ``outcome``'s counterexample on the composed automaton it was checked on;
    :class:`OrccadError` when the property holds (nothing to replay)."""
    automaton, mission = composition.automaton, composition.name
    script = outcome.script
    if outcome.holds or script is None:
        raise OrccadError(f"{outcome.kind} {mission}.{outcome.name} holds: there is no "
                          "counterexample to replay")
    reactor = Reactor(automaton)
    steps = []
    last = len(script.lines) - 1
    marked = script.loop_start if script.loop_start is not None else last
    for index, line in enumerate(script.lines):
        reaction = reactor.react(dict(line.inputs), line.time_ns)
        mark = "" if index != marked else (FAILS if script.loop_start is None else LOOPS)
        steps.append(ReplayStep(index + 1, line.time_ns, line.inputs, reaction.outputs,
                                reactor.state, reaction.status,
                                waiting_at(automaton, reactor.state),
                                _tasks(composition, reactor.state), mark, line.inside))
    return Replay(mission, outcome.kind, outcome.name, outcome.message, tuple(steps),
                  script.loop_start, script.note)


def script_instants(script: Script) -> list[Instant]:
    """The script's instants as ``orccad react`` reads them (the loop written once)."""
    return [Instant(number, dict(line.inputs), line.time_ns)
            for number, line in enumerate(script.lines, start=1)]


def _seconds(time_ns: int) -> str:
    return f"{time_ns / 1e9:.9f}".rstrip("0").rstrip(".") + " s"


def _value(name: str, value: Any) -> str:
    if value is None:
        return name
    if isinstance(value, bool):
        return f"{name}({'true' if value else 'false'})"
    if isinstance(value, tuple):
        return f"{name}([{', '.join(map(str, value))}])"
    return f"{name}({value!r})" if isinstance(value, str) else f"{name}({value})"


def step_lines(step: ReplayStep, path: str, text: str) -> list[str]:
    """The instant as text: its time, inputs, outputs, the statements it waits at (with
    their source line from ``text``, the file ``path``), the running tasks, its mark."""
    when = "" if step.time_ns is None else f" at {_seconds(step.time_ns)}"
    lines = [f"instant {step.number}{when}" + (f"   <- {step.mark}" if step.mark else "")]
    lines.append("  inputs:  " + (", ".join(_value(n, v) for n, v in step.inputs) or "-"))
    lines.append("  outputs: " + (", ".join(step.outputs) or "-"))
    source = text.splitlines()
    name = Path(path).name
    seen: set[tuple[str, int]] = set()
    for loc in sorted(step.waiting, key=lambda loc: (loc.file or "", loc.line)):
        where = Path(loc.file or name).name
        if loc.line <= 0 or (where, loc.line) in seen:
            continue
        seen.add((where, loc.line))
        statement = source[loc.line - 1].strip() if where == name and \
            loc.line <= len(source) else ""
        head = "  waiting at " if len(seen) == 1 else "             "
        lines.append(f"{head}{where}:{loc.line}  {statement}".rstrip())
    if not seen:
        lines.append("  waiting at no statement" if step.status == Status.RUNNING
                     else f"  the mission has ended: {step.status}")
    for task in step.tasks:
        where = Path(task.loc.file or name).name
        lines.append(f"  running: {task.task} (site {task.site}, run at {where}:{task.loc.line})")
    for inside in step.inside:
        lines.append(f"  in sub-mission {inside.label.text()}")
    return lines


def format_replay(replay_: Replay, path: str, text: str) -> str:
    """The whole counterexample, instant by instant (``orccad check --replay``)."""
    lines = [replay_.title]
    if replay_.note:
        lines.append(f"note: {replay_.note}")
    for index, step in enumerate(replay_.steps):
        if index == replay_.loop_start:
            lines.append("loop: the following instants repeat forever")
        lines += step_lines(step, path, text)
    return "\n".join(lines)
