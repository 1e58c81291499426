"""What the terminal UI does with a file, through the same functions as the CLI (no Textual).

- :func:`inspect_file`: ``orccad compile``'s pipeline (load, select, compile) as a
  :class:`FileView`: the source, its diagnostics with their lines, and a compile summary per
  mission;
- :func:`check_file`: ``orccad check``'s :func:`~orccad_app.verify.checker.check_mission`;
- :class:`LiveSession`: ``orccad run``'s plan and :class:`MissionRun`, observed by a
  :class:`~orccad_app.tui.live.LiveObserver`; its trace is exported by running it again
  (deterministic: the same run) with a trace recorder.
"""

from __future__ import annotations

import dataclasses
import os
import tempfile
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any, Callable

from orccad_app.diagnostics import OrccadError
from orccad_app.lang.literals import LiteralError, read_literal
from orccad_app.robottask.signals import RoleKind
from orccad_app.session import InputScript, RunOptions, RunSession
from orccad_app.tui.live import LiveObserver, LiveUpdate, SeenStates
from orccad_app.tui.pace import Pace
from orccad_app.tui.run_process import can_fork, run_forked

if TYPE_CHECKING:
    from orccad_app.verify.checker import MissionReport, PropertyOutcome

__all__ = ["FileDiagnostic", "FileView", "inspect_file", "check_file", "check_text",
           "LiveSession", "mission_files", "parse_value", "VALUE_HINTS", "inspect_text",
           "write_atomically", "ScriptedInputs", "failed_outcomes", "source_text",
           "one_line"]

VALUE_HINTS = {"int": "an integer, e.g. 3", "float": "a number, e.g. 0.8",
               "bool": "true or false", "vector": "numbers in brackets, e.g. [0.5, 0.5, 0.5]",
               "string": 'text in double quotes, e.g. "dock"', "duration": "seconds, e.g. 2.5"}
"""What the value of an input of each type looks like (for the prompt)."""


def parse_value(text: str, type_name: str, name: str | None = None) -> Any:
    """The value of input (or fault) ``name`` of type ``type_name`` typed as ``text`` (the
    literal grammar of :mod:`orccad_app.lang.literals`, as in ``--inject`` and input
    scripts); raises ``ValueError`` with its wording (never a silent default)."""
    try:
        return read_literal(text, type_name, name)
    except LiteralError as error:
        raise ValueError(error.message) from None


@dataclass(frozen=True)
class FileDiagnostic:
    """A message at a line of the source (``line`` 0 when it has no location)."""

    severity: str
    line: int
    col: int
    message: str

    def format(self) -> str:
        where = f"{self.line}:{self.col}: " if self.line else ""
        return f"{where}{self.severity}: {self.message}"


@dataclass
class FileView:
    """A file as the mission browser shows it."""

    path: str
    text: str
    diagnostics: list[FileDiagnostic] = field(default_factory=list)
    missions: list[str] = field(default_factory=list)
    summaries: dict[str, str] = field(default_factory=dict)
    inputs: dict[str, list[str]] = field(default_factory=dict)
    source: Any = None

    @property
    def ok(self) -> bool:
        return self.source is not None and not any(d.severity == "error"
                                                   for d in self.diagnostics)


def mission_files(paths: list[str]) -> list[str]:
    """The ``.orc`` files of ``paths`` (files as given, folders searched), sorted, unique."""
    found: dict[str, None] = {}
    for path in paths:
        item = Path(path)
        if item.is_dir():
            for file in sorted(item.glob("*.orc")):
                found[str(file)] = None
        elif item.exists():
            found[str(item)] = None
    return list(found)


def _diagnostic(severity: str, error: Any, path: str | None = None) -> FileDiagnostic:
    loc = getattr(error, "location", None) or getattr(error, "loc", None)
    message = getattr(error, "message", str(error))
    line = getattr(loc, "line", None) or 0
    if loc is not None and path is not None and line and \
            Path(loc.file).resolve() != Path(path).resolve():  # in an imported file
        return FileDiagnostic(severity, 0, 0, f"{loc}: {message}")
    return FileDiagnostic(severity, getattr(loc, "line", 0) or 0, getattr(loc, "col", 0) or 0,
                      message)


#: States the browser's summary compiles at most: a larger mission is summarized without its
#: automaton (a run builds the states it reaches; ``check`` explores them all).
SUMMARY_MAX_STATES = 2000


def _summary(source: Any, mission: Any) -> tuple[str, list[str]]:
    from orccad_app.pipeline import compose_mission
    from orccad_app.reactive.automaton import Automaton
    from orccad_app.reactive.compiler import StateBudgetExceeded
    from orccad_app.reactive.export import to_summary

    try:
        composition = compose_mission(source, mission, max_states=SUMMARY_MAX_STATES)
    except StateBudgetExceeded:
        composition = compose_mission(source, mission, lazy=True)
        tasks = ", ".join(dict.fromkeys(site.task for site in composition.sites)) or "-"
        inputs = composition.roles.own(s.name for s in composition.automaton.inputs)
        return (f"mission {mission.name}: more than {SUMMARY_MAX_STATES} states (a run builds "
                f"the states it reaches; orccad check explores them all)\n"
                f"  Robot-Tasks: {tasks}\n"), inputs
    automaton, sites = composition.automaton, composition.sites
    assert isinstance(automaton, Automaton)  # compiled whole (lazy=False)
    tasks = ", ".join(dict.fromkeys(site.task for site in sites)) or "-"
    inputs = composition.roles.own(s.name for s in automaton.inputs)
    head = (f"mission {mission.name}: {automaton.state_count} states, "
            f"{automaton.transition_count} transitions\n  Robot-Tasks: {tasks}\n")
    return head + to_summary(automaton), inputs


def source_text(path: str) -> str:
    """The text of ``path`` as the console shows and edits it, or a located
    :class:`OrccadError`: a regular file within the source budget (never a FIFO or
    ``/dev/zero``), UTF-8 (the first byte that is not, located), and not a binary file (its
    first NUL byte, located)."""
    from orccad_app.diagnostics import SourceLocation
    from orccad_app.pipeline import read_source

    text = read_source(path)
    nul = text.find("\0")
    if nul >= 0:
        start = text.rfind("\n", 0, nul) + 1
        raise OrccadError("a binary file (it holds a NUL byte), not plan-language text",
                          SourceLocation(path, text.count("\n", 0, nul) + 1, nul - start + 1))
    return text


def one_line(error: OrccadError) -> str:
    """``file:line:col: message`` of ``error``, without the source excerpt (a binary file's
    would be noise on the screen)."""
    return f"{error.location}: {error.message}" if error.location else error.message


def inspect_file(path: str, text: str | None = None) -> FileView:
    """Load, check and compile every mission of ``path`` (or of ``text``, an edited version of
    it); errors become diagnostics."""
    from orccad_app.pipeline import load

    try:
        edited = text is not None
        text = text if text is not None else source_text(path)
    except OrccadError as error:
        return FileView(path, "", [_diagnostic("error", error, path)])
    view = FileView(path, text)
    try:
        source = load(path, text=text if edited else None)
    except OrccadError as error:
        view.diagnostics.append(_diagnostic("error", error, path))
        return view
    view.source = source
    view.diagnostics += [_diagnostic("warning", w) for w in source.warnings]
    for mission in source.program.missions:
        view.missions.append(mission.name)
        try:
            view.summaries[mission.name], view.inputs[mission.name] = _summary(source, mission)
        except OrccadError as error:
            view.diagnostics.append(_diagnostic("error", error, path))
    return view


def inspect_text(path: str, text: str) -> FileView:
    """:func:`inspect_file` on an edited, unsaved ``text`` of ``path`` (its imports resolved
    from ``path``'s folder)."""
    view = inspect_file(path, text)
    view.source = None
    return view


def write_atomically(path: str | Path, write: Callable[[Path], None]) -> None:
    """Call ``write(tmp)`` on a temporary file next to ``path``, then rename it to ``path``:
    no reader ever sees a partial file, and a failed write leaves ``path`` as it was."""
    target = Path(path)
    handle, tmp = tempfile.mkstemp(prefix=f".{target.name}.", suffix=".part",
                                   dir=target.parent if str(target.parent) else ".")
    os.close(handle)
    try:
        write(Path(tmp))
        os.replace(tmp, target)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


def check_file(view: FileView, mission: str) -> Any:
    """``orccad check``'s report of ``mission`` (a ``MissionReport``)."""
    from orccad_app.pipeline import select_mission
    from orccad_app.verify.checker import check_mission

    return check_mission(view.source.program, select_mission(view.source, mission))


def check_text(report: Any) -> str:
    """The verdicts of a check report, with each counterexample's input script."""
    lines = [report.summary(data=False)]
    for outcome in report.outcomes:
        mark = "ok  " if outcome.holds else "FAIL"
        detail = f": {outcome.message}" if outcome.message else ""
        lines.append(f"  {mark}  {outcome.kind} {outcome.name}{detail}")
        if not outcome.holds and outcome.script is not None:
            script = outcome.script.text([f"counterexample to {outcome.name}"])
            lines += [f"        | {line}" for line in script.splitlines()]
    for prop in getattr(report, "signal_properties", ()):
        lines.append(f"  --    signal property {prop.name}: not proved; judged on runs")
    failed = sum(1 for o in report.outcomes if not o.holds)
    lines.append("all properties hold" if not failed else f"{failed} failed")
    return "\n".join(lines)


ScriptedInputs = InputScript
"""The inputs of a counterexample, run against the plant (the Check tab's "run"):
:meth:`InputScript.of` a failed property's outcome."""


def failed_outcomes(report: MissionReport) -> list[PropertyOutcome]:
    """The outcomes of a check report that failed with a counterexample."""
    return [o for o in report.outcomes if not o.holds and o.script is not None]


class LiveSession:
    """One live run of ``mission`` of ``path`` (see the module docstring).

    :param post: receives each :class:`~orccad_app.tui.live.LiveUpdate`.
    :param speed: initial factor (``None`` as fast as possible, ``0`` paused).
    :param script: a :class:`ScriptedInputs` (a counterexample run against the plant): its
        inputs are injected at its instants' times, as ``orccad run --inject-from`` does.
    :param setting: a campaign's run (a :class:`~orccad_app.campaign.setting.RunSetting`)
        replayed live: its overrides, injections (raised ``by``), seed and horizon.
    :param wait_for_screen: see :class:`~orccad_app.tui.live.LiveObserver` (the run screen
        calls ``observer.frame_taken()`` after each update).
    :param own_process: run in a child process forked once the run is planned
        (:mod:`orccad_app.tui.run_process`: the screen's drawing then never holds the run
        back); where ``os.fork`` is missing, in the calling thread.
    """

    def __init__(self, path: str, mission: str | None, post: Callable[[LiveUpdate], None], *,
                 speed: float | None = 1.0, seed: int = 0, until_s: float | None = None,
                 script: Any = None, setting: Any = None, by: str = "",
                 wait_for_screen: bool = False, own_process: bool = False) -> None:
        from orccad_app.pipeline import load, select_mission

        source = load(path)
        self.path, self.seed = path, seed
        self.text = source.text
        """The mission file's text (the run screen shows where the mission waits in it)."""
        selected = select_mission(source, mission)
        self.mission = selected.name
        if setting is not None:  # a campaign's run: its overrides, injections, seed, horizon
            options = setting.options(injected_by=by, script=script)
            self.seed = setting.seed
        else:
            options = RunOptions(script=script, seed=seed, until_s=until_s)
        self.session = RunSession(source, selected, options)
        """The run, planned (:class:`~orccad_app.session.RunSession`)."""
        self.run = self.session.run
        plan = self.session.plan
        self.inputs = [s for s in plan.automaton.inputs if plan.roles.is_own(s.name)]
        """The mission's declared inputs (``SignalDecl``)."""
        events = plan.roles.of_kind(RoleKind.EVENT)
        self.events = [s.name for s in plan.automaton.inputs if s.name in events]
        """Observer events ``X.E`` (what an observer of task ``X`` raises for ``E``)."""
        self.script = script
        """The counterexample run against the plant, or ``None``."""
        self.scripted = list(self.session.injected)
        """The script's (or the campaign run's) injections, for the report."""
        self.setting = setting
        """The campaign run replayed (a :class:`~orccad_app.campaign.setting.RunSetting`),
        or ``None``."""
        self.faults = self.run.faults()
        """Plant faults ``ROBOT.FAULT`` -> description (robot types with a plant extension)."""
        self.pace = Pace(speed)
        self.observer = LiveObserver(self.run, post, self.pace, scripted={
            (record.time_ns, record.name) for record in self.scripted},
            scripted_by=script.by if script is not None else by, wait_for_screen=wait_for_screen)
        self.session.add_observer(self.observer)
        self.own_process = own_process and can_fork()
        self.automaton: Any = SeenStates() if self.own_process else plan.automaton
        """The automaton's states as the screen reads them (:mod:`orccad_app.tui.status`):
        the plan's (lazy) automaton, or the states the run's process has shown."""
        self.result: Any = None
        self.run_report: Any = None
        """The :class:`~orccad_app.session.RunReport` of the finished run."""

    def execute(self) -> Any:
        """Run to the end (blocking: call it from a worker thread); the ``RunResult``."""
        if self.own_process:
            post = self.observer.post

            def shown(update: LiveUpdate) -> None:  # learn the states, then show them
                self.automaton.learn(update.states)
                post(update)

            ended = run_forked(self._execute_here, self.observer, shown)
            self.observer.adopt(ended)
            result = dataclasses.replace(ended.report.result, modules=self.run.plan.tcs.modules)
            self.run_report = dataclasses.replace(ended.report, result=result)
        else:
            self.run_report = self._execute_here()
        self.result = self.run_report.result
        return self.result

    def _execute_here(self) -> Any:
        report = self.session.execute()
        self.observer.flush(self.run.kernel.now)
        return report

    def report(self) -> str:
        """``orccad run``'s text report of the finished run (with the properties' verdicts)
        and what the user raised, the real-time ratio computed without the time spent paused
        (said on the second line)."""

        paused = self.pace.paused_s
        report = self.run_report
        injected = sorted([*report.injections, *self.observer.injected],
                          key=lambda record: record.time_ns)
        report = dataclasses.replace(report, injections=tuple(injected))
        if paused > 0:
            report = dataclasses.replace(report, result=dataclasses.replace(
                report.result, wall_time_s=max(report.result.wall_time_s - paused, 1e-9)))
        lines = report.text().split("\n")
        if paused > 0:
            lines.insert(2, f"  paused {paused:.2f} s of wall time, not counted above")
        return "\n".join(lines)

    def export(self, path: str, *, overwrite: bool = False,
               progress: Callable[[float], object] | None = None) -> str:
        """Write the trace (``.csv`` or ``.mcap``) to ``path`` and return it: atomically (a
        temporary file renamed once complete), never over an existing file unless
        ``overwrite`` (``FileExistsError``)."""
        from orccad_app.trace import TRACE_FORMATS

        suffix = Path(path).suffix.lower()
        if suffix not in TRACE_FORMATS:
            raise OrccadError(f"{path}: unknown trace format '{suffix or '(none)'}' (use "
                              f"{' or '.join(TRACE_FORMATS)})")
        if Path(path).exists() and not overwrite:
            raise FileExistsError(path)

        def write(tmp: Path) -> None:
            named = tmp.with_suffix(suffix)  # the writer picks the format by the suffix
            try:
                self._replay_trace(str(named), progress)
                os.replace(named, tmp)
            finally:
                named.unlink(missing_ok=True)

        write_atomically(path, write)
        return path

    def _replay_trace(self, path: str, progress: Callable[[float], object] | None) -> None:
        """Run the finished run again with a trace recorder: the same options (plan, seed,
        horizon, injections), the user's inputs as ``--inject`` at the instants they took
        effect (the same run, :mod:`orccad_app.tui.user_inputs`), ended at the same reaction
        when the user aborted it. The live run records no trace: a trace costs more than the
        run."""

        from orccad_app.mission.injection import Injection, PlantFault

        tick = self.run.tick_ns
        user = []
        for record in self.observer.injected:
            last = record.time_ns if record.until_ns is None else record.until_ns
            fault = PlantFault.named(record.name) if record.fault else None
            user += [Injection(record.name, time_ns, record.value, fault)
                     for time_ns in range(record.time_ns, last + 1, tick)]
        options = self.session.options
        replay = RunSession(self.session.source, self.session.mission, dataclasses.replace(
            options, injections=(*options.injections, *user), trace=path, trace_format=None,
            trace_file=self.path, observers=()))
        end_ns = self.result.sim_time_ns if self.result is not None else self.run.until_ns
        replay.add_observer(_Replaying(replay.run, self.observer.aborted_at, end_ns, progress))
        replay.execute()
        if progress is not None:
            progress(1.0)


class _Replaying:
    """Ends a replayed run at the reaction where the live run was aborted (``abort_at``, the
    count of reactions then; ``None``: not aborted) and reports its progress."""

    def __init__(self, run: Any, abort_at: int | None, end_ns: int,
                 progress: Callable[[float], object] | None) -> None:
        self.run, self.abort_at, self.end_ns, self.progress = run, abort_at, end_ns, progress
        self.reactions = 0

    def on_reaction(self, t_ns: int, inputs: tuple[str, ...], outputs: tuple[str, ...],
                    status: str) -> None:
        self.reactions += 1
        if self.abort_at is not None and self.reactions >= self.abort_at:
            self.run.abort("stopped by the user")
        elif self.progress is not None and self.reactions % 2000 == 0 and self.end_ns:
            self.progress(min(1.0, t_ns / self.end_ns))
