"""The run's Module-Task backend, picked from its options: :func:`module_task_backend`.

``RunOptions.execution`` says where the Module-Tasks' jobs run
(:class:`~orccad_app.session.options.Execution`); the façade makes the
:class:`~orccad_app.mission.backend.ModuleTaskBackend` once the mission is planned and hands
it to the :class:`~orccad_app.mission.run.MissionRun`: in-process
(:class:`~orccad_app.mission.backend.InProcess`), lockstep
(:class:`~orccad_app.sil.lockstep.LockstepBackend`) or real time
(:class:`~orccad_app.sil.realtime.backend.RealtimeBackend`), the last two building and
starting the controller process of the plan.

What the real-time backend does not model is refused before anything is built
(:func:`refuse_in_realtime`): EDF, a context-switch overhead and a bus delay are the
executive's simulated timing; the controller's threads run at fixed priorities under
SCHED_FIFO, pay the machine's real context switches and exchange through their own memory.
"""

from __future__ import annotations

from orccad_app.diagnostics import OrccadError
from orccad_app.mission.backend import InProcess, ModuleTaskBackend
from orccad_app.mission.budget import check_run_budget
from orccad_app.mission.plan import MissionPlan
from orccad_app.session.options import Execution, RunOptions

__all__ = ["module_task_backend", "refuse_in_realtime"]


def refuse_in_realtime(options: RunOptions) -> None:
    """Refuse the options the real-time backend cannot honour, naming each and why."""
    why = "use --lockstep, which runs the executive's timing model"
    if options.scheduler != "fp":
        raise OrccadError(f"orccad sil --realtime: --scheduler {options.scheduler}: the "
                          f"controller's threads run at fixed priorities under SCHED_FIFO, "
                          f"the executive's {options.scheduler.upper()} is simulated ({why})")
    if options.context_switch_ns:
        raise OrccadError("orccad sil --realtime: --context-switch-us: the controller's "
                          "threads pay the machine's own context switches (measured in the "
                          f"release lateness), a declared overhead is simulated ({why})")
    if not options.delays.ideal:
        raise OrccadError("orccad sil --realtime: --exchange-us and --jitter-us model the "
                          "delays a real controller adds; here they are the machine's own "
                          f"(measured in the release lateness) ({why})")
    if options.bus_transfer_ns:
        raise OrccadError("orccad sil --realtime: --bus-us: the controller's Module-Tasks "
                          "exchange through their own memory, a bus delay is simulated "
                          f"({why})")


def module_task_backend(options: RunOptions, plan: MissionPlan,
                        until_ns: int) -> ModuleTaskBackend:
    """The backend of ``options.execution`` for ``plan``; a controller process is built and
    started for lockstep and real time, after the run's cost (``until_ns``) and what real
    time cannot honour are checked (the caller closes the backend)."""
    if options.execution is Execution.SIMULATED:
        return InProcess()
    check_run_budget(plan, until_ns)  # the run's cost, refused before anything is built
    controller = options.controller
    if options.execution is Execution.REALTIME:
        from orccad_app.sil.realtime.backend import RealtimeBackend

        refuse_in_realtime(options)
        return RealtimeBackend(plan, controller.source, controller.build_dir,
                               controller.heartbeat_s, controller.prebuilt)
    from orccad_app.sil.lockstep import LockstepBackend

    return LockstepBackend(plan, controller.source, controller.build_dir, controller.heartbeat_s,
                           controller.prebuilt)
