"""``orccad sil`` through the run façade: :class:`ControllerRuns`, the session's run factory.

A SIL run is an ``orccad run`` (:class:`~orccad_app.session.RunSession`: the same plan,
injections, input script, overrides, trace, property monitor, observers and report) whose
:class:`~orccad_app.mission.run.MissionRun` is made by :class:`ControllerRuns`: once the
session has planned the mission, it emits and builds the controller of the plan, starts it,
and returns the run of the mode — lockstep (the executive's timing model, every job computed
by the controller: :mod:`.lockstep`) or real time (the controller's threads on the wall clock,
this process the plant server: :mod:`.realtime`). The controller is ended and reaped when
:meth:`ControllerRuns.close` runs (use it as a context manager around the session), however
the run ended.

What the real-time mode does not model is refused before anything is built
(:func:`refuse_in_realtime`): EDF, a context-switch overhead and a bus delay are the
executive's simulated timing; the controller's threads run at fixed priorities under
SCHED_FIFO, pay the machine's real context switches and exchange through their own memory.
"""

from __future__ import annotations

import enum
from contextlib import ExitStack
from pathlib import Path
from typing import Any

from orccad_app.diagnostics import OrccadError
from orccad_app.mission.plan import MissionPlan
from orccad_app.mission.run import MissionRun
from orccad_app.session import RunOptions
from orccad_app.sil.controller import DEFAULT_HEARTBEAT_S, ControllerProcess

__all__ = ["SilMode", "ControllerRuns", "refuse_in_realtime"]


class SilMode(enum.Enum):
    """How the controller process runs against the plant."""

    LOCKSTEP = "lockstep"
    """One exchange per job over a Unix socket; the plant advances by the declared times."""
    REALTIME = "realtime"
    """Real threads on the wall clock; the plant over shared memory."""


def refuse_in_realtime(options: RunOptions) -> None:
    """Refuse the options the real-time mode cannot honour, naming each and why."""
    why = "use --lockstep, which runs the executive's timing model"
    if options.scheduler != "fp":
        raise OrccadError(f"orccad sil --realtime: --scheduler {options.scheduler}: the "
                          f"controller's threads run at fixed priorities under SCHED_FIFO, "
                          f"the executive's {options.scheduler.upper()} is simulated ({why})")
    if options.context_switch_ns:
        raise OrccadError("orccad sil --realtime: --context-switch-us: the controller's "
                          "threads pay the machine's own context switches (measured in the "
                          f"release lateness), a declared overhead is simulated ({why})")
    if options.bus_transfer_ns:
        raise OrccadError("orccad sil --realtime: --bus-us: the controller's Module-Tasks "
                          "exchange through its own memory, a bus delay is simulated "
                          f"({why})")


class ControllerRuns:
    """The run factory of a SIL session (``RunOptions.run_factory``): see the module
    docstring.

    :param mode: lockstep or real time.
    :param file: the mission file (named in the generated sources).
    :param build_dir: where the generated C goes (default a temporary directory).
    :param heartbeat_s: the controller must answer each request within this [s].
    """

    def __init__(self, mode: SilMode, file: str, build_dir: Path | None = None,
                 heartbeat_s: float = DEFAULT_HEARTBEAT_S) -> None:
        self.mode, self.file, self.build_dir, self.heartbeat_s = mode, file, build_dir, heartbeat_s
        self.controller: ControllerProcess | None = None
        """The controller process, once the session made the run."""
        self.run: MissionRun | None = None
        """The run made (a :class:`~orccad_app.sil.realtime.RealtimeRun` in real time)."""
        self._stack = ExitStack()

    def __call__(self, plan: MissionPlan, **options: Any) -> MissionRun:
        """The run of ``plan``, its Module-Tasks in a controller started for it."""
        if self.run is not None:
            raise OrccadError("orccad sil: one controller runs one mission run")
        if self.mode is SilMode.REALTIME:
            from orccad_app.sil.realtime import RealtimeRun, realtime

            table, controller, shared = self._stack.enter_context(
                realtime(plan, self.file, self.build_dir, self.heartbeat_s))
            options.pop("realtime", None)  # paced at 1 by the real-time run itself
            self.controller = controller
            self.run = RealtimeRun(plan, table, controller, shared, **options)
        else:
            from orccad_app.sil.lockstep import lockstep

            self.controller = self._stack.enter_context(
                lockstep(plan, self.file, self.build_dir, self.heartbeat_s))
            self.run = MissionRun(plan, **options)
        return self.run

    def timings(self) -> list[Any] | None:
        """What the real-time run measured per Module-Task (before :meth:`close`; the run's
        statistics filled with it), ``None`` in lockstep."""
        from orccad_app.sil.realtime import RealtimeRun

        return self.run.timings() if isinstance(self.run, RealtimeRun) else None

    def close(self) -> None:
        """End and reap the controller (and remove its shared memory)."""
        self._stack.close()

    def __enter__(self) -> ControllerRuns:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()
