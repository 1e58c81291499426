"""One way to run a mission: the run façade used by ``orccad run``, campaigns and the TUI.

A run is always assembled the same way (:class:`RunSession`): plan the mission with its
overrides, type the injections against the plan's inputs, build the processors and the bus,
make the Module-Task backend of the options' :class:`Execution` (in this process, or in a
controller process in lockstep or real time) and the
:class:`~orccad_app.mission.run.MissionRun`, attach the property monitor, the trace
and the caller's observers, run with Ctrl-C and SIGTERM scoped to the run, and return one
:class:`RunReport` (the result, what was injected from outside, the properties' verdicts)
that every consumer renders::

    from orccad_app.session import RunOptions, run_mission

    report = run_mission(source, mission, RunOptions(seed=3, until_s=10.0))
    print(report.text())          # orccad run's text report
    report.as_dict()              # orccad run --json's object
    report.exit_status            # 0, or 1 for a mission not done or a property violated

:class:`RunOptions` holds everything a caller may choose (:mod:`.options`); a caller that
needs the plan before the run (to build an observer from it, or to show it) makes a
:class:`RunSession`, adds observers, then calls :meth:`RunSession.execute`.
"""

from orccad_app.session.options import ControllerOptions, Execution, InputScript, RunOptions
from orccad_app.session.report import RunReport
from orccad_app.session.run import RunSession, run_mission

__all__ = ["ControllerOptions", "Execution", "InputScript", "RunOptions", "RunReport",
           "RunSession", "run_mission"]
