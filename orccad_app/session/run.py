"""The run façade: :class:`RunSession` assembles, runs and reports one run of a mission.

Every way of running a mission goes through here (``orccad run``, campaigns, the TUI):

1. **plan** the mission with the options' overrides
   (:func:`~orccad_app.mission.overrides.plan_with_overrides`; a caller that compiled the
   mission already passes its composition);
2. **type** the injections once, against the plan's inputs (a pure input takes no value, a
   valued one a value of its declared type; plant faults finite), and add the input script's;
3. build the **processors** (every processor of the plan with the options' scheduler and
   context switch) and the **bus**, the Module-Task **backend** of the options' execution
   (:mod:`.backends`: in-process, or a controller process in lockstep or real time), and the
   :class:`~orccad_app.mission.run.MissionRun`;
4. attach the **property monitor** (:class:`~orccad_app.properties.PropertyMonitor`), the
   **trace** (:mod:`orccad_app.trace`) and the caller's **observers**;
5. **run**, Ctrl-C and SIGTERM scoped to the run when asked (:mod:`.signals`), close the
   trace, the observers' files and the backend (a controller process ended and reaped), and
   return one :class:`~orccad_app.session.report.RunReport`.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

from orccad_app.diagnostics import OrccadError
from orccad_app.executive.bus import Bus
from orccad_app.executive.processor import Processor
from orccad_app.lang import ast
from orccad_app.mission.backend import ModuleTaskBackend
from orccad_app.mission.injection import Injection, typed_injections
from orccad_app.mission.overrides import plan_with_overrides
from orccad_app.mission.plan import MissionPlan
from orccad_app.mission.run import MissionRun
from orccad_app.pipeline import Source
from orccad_app.properties.evaluate import PropertyMonitor
from orccad_app.session.backends import module_task_backend
from orccad_app.session.options import DEFAULT_UNTIL_S, MAX_RUN_S, RunOptions
from orccad_app.session.report import RunReport
from orccad_app.session.signals import signals_end_the_run
from orccad_app.trace.report import InjectionRecord
from orccad_app.trace.run_topics import trace_recorder
from orccad_app.trace.state_topics import VerdictSample
from orccad_app.trace.writers import open_trace, sensor_ports

__all__ = ["RunSession", "run_mission"]


class RunSession:
    """One run of ``mission`` of ``source``, planned and ready (see the module docstring).

    :param source: the loaded file (:func:`~orccad_app.pipeline.load`).
    :param mission: the mission (:func:`~orccad_app.pipeline.select_mission`).
    :param options: the run's :class:`~orccad_app.session.options.RunOptions`.
    :param composition: the mission's composition when the caller has compiled it already
        (a campaign compiles once for all its runs).

    Bad input (an unknown input, a value of the wrong type, an injection after the horizon, an
    unknown fault, an override the mission does not have) raises a located
    :class:`~orccad_app.diagnostics.OrccadError` here, before anything runs.
    """

    def __init__(self, source: Source, mission: ast.Mission, options: RunOptions = RunOptions(),
                 *, composition: Any = None) -> None:
        self.source, self.mission, self.options = source, mission, options
        self.plan: MissionPlan = plan_with_overrides(source, mission, options.overrides,
                                                     composition)
        """The mission's plan (run sites, one TCS, plants)."""
        until_s = options.until_s
        if until_s is None:
            until_s = self.plan.run_horizon_s(DEFAULT_UNTIL_S)
        self.until_ns = int(round(min(until_s, MAX_RUN_S) * 1e9))
        """The simulated-time limit [ns]."""
        injections, self.injected = self._injections()
        """The records of what the options inject (the report lists them)."""
        processors = [Processor(name, options.scheduler, options.context_switch_ns)
                      for name in self.plan.processor_names]
        self.backend: ModuleTaskBackend = module_task_backend(options, self.plan,
                                                              self.until_ns)
        """Where the Module-Tasks' jobs run (:mod:`.backends`); closed when the run ends."""
        self._closing: list[Callable[[], None]] = []
        try:
            self.run = MissionRun(self.plan, seed=options.seed, until_ns=self.until_ns,
                                  injections=injections, processors=processors,
                                  bus=Bus(transfer_ns=options.bus_transfer_ns),
                                  observers=options.observers, realtime=options.realtime,
                                  backend=self.backend, delays=options.delays)
            """The :class:`~orccad_app.mission.run.MissionRun` (observe it, do not reach
            in)."""
            self.monitor = PropertyMonitor(source.program, mission, self.run)
            """Judges every property of the mission on the run."""
            if options.trace is not None:
                self._open_trace(options.trace)
        except BaseException:  # a refused option: the controller process is ended at once
            self.backend.close()
            raise
        self.report: RunReport | None = None
        """The report, once :meth:`execute` has run."""

    def _injections(self) -> tuple[list[Injection], list[InjectionRecord]]:
        """The injections typed against the plan's inputs, and their records."""
        options, inputs = self.options, self.plan.automaton.inputs
        for injection in options.injections:
            value = injection.value
            if injection.fault is not None and isinstance(value, float) and not math.isfinite(value):
                raise OrccadError(f"--inject {injection.name}: the value must be a finite "
                                  f"number, got {value}")
        typed = typed_injections(options.injections, inputs)
        records = [InjectionRecord(i.time_ns, i.name, i.value, i.fault is not None,
                                   options.injected_by)
                   for i in typed]
        script = options.script
        if script is not None:
            scripted = script.injections(self.plan.tick_ns, inputs)
            typed += scripted
            records += [InjectionRecord(i.time_ns, i.name, i.value, False, script.by)
                        for i in scripted]
        return typed, records

    def _open_trace(self, path: str) -> None:
        metadata = {"mission": self.mission.name,
                    "file": self.options.trace_file or self.source.path,
                    "seed": str(self.options.seed)}
        sensors = sensor_ports(self.plan)
        if self.options.trace_format == "rosbag2":
            from orccad_app.ros2.bag import Rosbag2TraceWriter

            self.record(Rosbag2TraceWriter(path, metadata, sensors))
        else:
            self.record(open_trace(path, metadata, sensors, self.options.trace_format))

    def record(self, writer: Any) -> None:
        """Write the run's trace to ``writer`` (a CSV, MCAP or live Foxglove writer) as
        ``orccad run --trace`` does: the events, and for a topic writer the run's state
        topics and the properties' running verdicts; closed when the run ends."""
        recorder = trace_recorder(writer, self.run, verdicts=self.verdict_samples)
        self.add_observer(recorder, recorder.close)

    def verdict_samples(self) -> list[VerdictSample]:
        """Every property's verdict on the run so far (the trace's ``/properties`` topics)."""
        return [VerdictSample(r.name, r.verdict.value, r.robustness, r.unit, r.samples)
                for r in self.monitor.running()]

    def add_observer(self, observer: Any, close: Callable[[], None] | None = None) -> None:
        """Observe the run (before :meth:`execute`); ``close`` is called once it ends, even
        when it fails (a file the observer writes)."""
        self.run.add_observer(observer)
        if close is not None:
            self._closing.append(close)

    def execute(self, *, starting: Callable[[MissionRun], None] | None = None) -> RunReport:
        """Run to the end and return the report (also kept as :attr:`report`); ``starting``
        is called just before, within the run's signal handling (a wait that Ctrl-C ends:
        the run then ends ``aborted`` at once, its report and trace written). The trace's
        disk full or gone is an :class:`~orccad_app.diagnostics.OrccadError` naming it."""
        try:
            try:
                with signals_end_the_run(self.run, enabled=self.options.signals_end_run):
                    if starting is not None:
                        starting(self.run)
                    result = self.run.run()
            finally:
                try:
                    for close in self._closing:
                        close()
                finally:
                    self.backend.close()
        except OSError as error:
            if self.options.trace is None:
                raise
            raise OrccadError(f"{self.options.trace}: cannot write the trace: "
                              f"{error.strerror or error}") from None
        records = sorted(self.injected, key=lambda record: record.time_ns)
        self.report = RunReport(result, tuple(records), tuple(self.monitor.results()))
        return self.report


    def close(self) -> None:
        """End what the session holds without running (a controller process; the trace's
        and observers' files): for a session that is not executed."""
        try:
            for close in self._closing:
                close()
        finally:
            self._closing = []
            self.backend.close()

    def __enter__(self) -> RunSession:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


def run_mission(source: Source, mission: ast.Mission, options: RunOptions = RunOptions(),
                *, composition: Any = None) -> RunReport:
    """Plan, run and report ``mission`` of ``source`` (:class:`RunSession`, then
    :meth:`RunSession.execute`)."""
    return RunSession(source, mission, options, composition=composition).execute()
