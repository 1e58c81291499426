"""What a caller chooses about one run: :class:`RunOptions` and :class:`InputScript`."""

from __future__ import annotations

import enum
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from orccad_app.executive.delays import ControllerDelays
from orccad_app.mission.injection import Injection
from orccad_app.mission.overrides import PlanOverrides
from orccad_app.reactive.ir import SignalDecl
from orccad_app.reactive.script import Instant
from orccad_app.sil.build.executable import Prebuilt
from orccad_app.sil.controller.process import DEFAULT_HEARTBEAT_S

__all__ = ["ControllerOptions", "DEFAULT_UNTIL_S", "Execution", "InputScript", "MAX_RUN_S",
           "RunOptions"]

MAX_RUN_S = 365 * 24 * 3600.0
"""The longest run [s] (one year of simulated time)."""
DEFAULT_UNTIL_S = 60.0
"""The default simulated-time limit [s], unless a robot type declares a longer one."""


@dataclass(frozen=True)
class InputScript:
    """The inputs of an input script raised at its instants' times
    (:mod:`orccad_app.mission.scripted`): an ``orccad check`` counterexample, from a file
    (``orccad run --inject-from``) or from a check report (the TUI's "run against the plant").

    :param by: who raised them, for the report (``--inject-from ce.in``, ``counterexample
        to P``).
    :param instants: the script's instants, when already read.
    :param path: the script file, read against the plan's inputs when the run is planned.
    """

    by: str
    instants: tuple[Instant, ...] = ()
    path: str | None = None

    @classmethod
    def from_file(cls, path: str) -> InputScript:
        """The script in file ``path`` (read when the run is planned)."""
        return cls(f"--inject-from {path}", path=path)

    @classmethod
    def of(cls, outcome: Any) -> InputScript:
        """The counterexample of a failed property (a check report's ``PropertyOutcome``)."""
        from orccad_app.verify.replay import script_instants

        return cls(f"counterexample to {outcome.name}", tuple(script_instants(outcome.script)))

    def read(self, inputs: tuple[SignalDecl, ...]) -> tuple[Instant, ...]:
        """The instants, the file parsed against the automaton's ``inputs`` (located errors)."""
        if self.path is None:
            return self.instants
        from orccad_app.pipeline import read_source
        from orccad_app.reactive.script import parse_script

        return tuple(parse_script(read_source(self.path), self.path, inputs))

    def injections(self, tick_ns: int, inputs: tuple[SignalDecl, ...] = ()) -> list[Injection]:
        """The inputs raised at the instants' times, one reaction ``tick_ns`` apart at least."""
        from orccad_app.mission.scripted import script_injections

        return script_injections(self.read(inputs), tick_ns)


class Execution(enum.Enum):
    """Where the Module-Tasks' jobs run and what steps the automaton (the run façade picks
    the run's :class:`~orccad_app.mission.backend.ModuleTaskBackend` from it)."""

    SIMULATED = "simulated"
    """In this process: the executive runs the Python Module-Tasks on simulated processors,
    the Python reactor reacts (``orccad run``)."""
    LOCKSTEP = "lockstep"
    """In the controller process, one exchange per job over a Unix socket, on the executive's
    timing model (``orccad sil --lockstep``)."""
    REALTIME = "realtime"
    """On the controller process's real-time threads on the wall clock, the plant over
    shared memory (``orccad sil --realtime``)."""


@dataclass(frozen=True)
class ControllerOptions:
    """The controller process of a lockstep or real-time run.

    :param source: the mission file, named in the generated sources.
    :param build_dir: where the generated C goes (``None``: a temporary directory).
    :param heartbeat_s: the controller must answer each request within this [wall s].
    :param prebuilt: a controller built elsewhere (``--controller``, maybe through a
        ``--controller-wrapper``), run instead of building one.
    """

    source: str = ""
    build_dir: Path | None = None
    heartbeat_s: float = DEFAULT_HEARTBEAT_S
    prebuilt: Prebuilt | None = None


@dataclass(frozen=True)
class RunOptions:
    """Everything a caller chooses about one run (``orccad run``'s options).

    :param overrides: ``--set`` and ``--timing`` (:class:`~orccad_app.mission.overrides.PlanOverrides`).
    :param injections: inputs and plant faults raised at given instants (``--inject``),
        parsed; the session types their values against the plan's inputs.
    :param injected_by: who raised ``injections``, for the report (``--inject``, or the
        campaign run a console replays).
    :param script: an input script whose inputs are raised too (``--inject-from``).
    :param seed: the seed of execution times and sensor noise.
    :param until_s: the simulated-time limit [s]; ``None``: :data:`DEFAULT_UNTIL_S`, or the
        robot type's longer ``run_horizon_s``.
    :param scheduler: every processor's policy, ``fp`` or ``edf``.
    :param context_switch_ns: the context-switch overhead [ns].
    :param bus_transfer_ns: the bus's transfer time per message [ns].
    :param delays: the exchange delay and release jitter a real controller adds
        (``--exchange-us``, ``--jitter-us``: :mod:`orccad_app.executive.delays`); default
        none, the executive's ideal exchange.
    :param realtime: ``None`` as fast as possible, else simulated s per wall s.
    :param trace: a trace file to write (``.csv`` or ``.mcap``; a directory for
        ``rosbag2``), ``None`` for none.
    :param trace_format: ``csv``, ``mcap`` or ``rosbag2`` (the ``[ros2]`` extra); ``None``:
        by the file's suffix.
    :param trace_file: the mission file as the trace's metadata names it (default the
        source's path).
    :param observers: observers of the run (executive callbacks and the mission hooks,
        :mod:`orccad_app.mission.observer`).
    :param execution: where the Module-Tasks' jobs run (:class:`Execution`; the façade
        makes the run's backend from it).
    :param controller: the controller process of a lockstep or real-time run.
    :param signals_end_run: Ctrl-C and SIGTERM end the run after the current event (status
        ``aborted``, report and trace complete), a second one at once; the handlers are
        installed for the run only, and only from the main thread.
    """

    overrides: PlanOverrides = field(default_factory=PlanOverrides)
    injections: tuple[Injection, ...] = ()
    injected_by: str = "--inject"
    script: InputScript | None = None
    seed: int = 0
    until_s: float | None = None
    scheduler: str = "fp"
    context_switch_ns: int = 0
    bus_transfer_ns: int = 0
    delays: ControllerDelays = field(default_factory=ControllerDelays)
    realtime: float | None = None
    trace: str | None = None
    trace_format: str | None = None
    trace_file: str | None = None
    observers: tuple[Any, ...] = ()
    execution: Execution = Execution.SIMULATED
    controller: ControllerOptions = field(default_factory=ControllerOptions)
    signals_end_run: bool = False
