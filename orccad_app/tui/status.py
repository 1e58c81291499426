"""What the run screen says about a live run, as text (no Textual: testable alone).

- :class:`SpeedMeter`: the actual speed (simulated seconds per wall second, pauses excluded)
  from successive :class:`~orccad_app.tui.live.LiveUpdate` s;
- :func:`status_text`: time and progress against the horizon, requested and actual speed,
  paused, a warning when the run lags, and where the mission waits;
- :func:`waiting_lines`: the source lines of the statements the automaton's state waits at;
- :func:`rta_text`: each running Robot-Task's RTA, its current phase marked;
- :func:`tcs_rows`: the TCS's Module-Tasks with processor, timing, load and misses.
"""

from __future__ import annotations

from collections import deque
from pathlib import Path
from typing import Any

from orccad_app.reactive.status import Status
from orccad_app.robottask.labels import Phase
from orccad_app.tui.live import LiveUpdate

__all__ = ["SpeedMeter", "status_text", "waiting_lines", "run_site_lines", "running_sites",
           "tasks_in_state", "elsewhere", "waiting_elsewhere", "where_text", "rta_text", "tcs_rows", "LAG_RATIO"]

LAG_RATIO = 0.8
"""The run lags when its actual speed is below this fraction of the requested one."""

_PHASE_TEXT = {1: "waiting for its synchronization pre-conditions",
               2: "measuring its measurement pre-conditions",
               3: "running its control law"}


class SpeedMeter:
    """Actual speed over the last ``span_s`` wall seconds of updates, pauses excluded."""

    def __init__(self, span_s: float = 2.0) -> None:
        self.span_s = span_s
        self._points: deque[tuple[float, float, float]] = deque()  # (wall, paused, sim) [s]

    def reset(self) -> None:
        """Forget the history (the requested speed changed)."""
        self._points.clear()

    def add(self, update: LiveUpdate) -> None:
        self._points.append((update.wall_s, update.paused_s, update.time_ns / 1e9))
        while len(self._points) > 2 and update.wall_s - self._points[0][0] > self.span_s:
            self._points.popleft()

    @property
    def actual(self) -> float | None:
        """Simulated seconds per running wall second, ``None`` before two updates."""
        if len(self._points) < 2:
            return None
        (w0, p0, s0), (w1, p1, s1) = self._points[0], self._points[-1]
        running = (w1 - w0) - (p1 - p0)
        return (s1 - s0) / running if running > 1e-3 else None


def _waiting(session: Any, state: int | None) -> tuple[Any, ...]:
    """The locations state ``state`` waits at (sub-missions' call sites included)."""
    from orccad_app.verify.replay import waiting_at

    return () if state is None else waiting_at(session.automaton, state)


def _in_file(locations: Any, path: str) -> list[int]:
    name = Path(path).name
    return sorted({loc.line for loc in locations
                   if loc.line > 0 and Path(loc.file or name).name == name})


def waiting_lines(session: Any, state: int | None) -> list[int]:
    """Lines of the mission's file where state ``state`` of its automaton is paused (a
    statement of an imported sub-mission shows as its ``run mission`` line)."""
    return _in_file(_waiting(session, state), session.path)


def elsewhere(locations: Any, path: str) -> list[str]:
    """``homing.orc:26``: the locations of ``locations`` in files other than ``path``."""
    name = Path(path).name
    return list(dict.fromkeys(f"{Path(loc.file).name}:{loc.line}" for loc in locations
                              if loc.line > 0 and Path(loc.file or name).name != name))


def waiting_elsewhere(session: Any, state: int | None) -> list[str]:
    """Where ``state`` waits in other files than the mission's (imported sub-missions)."""
    return elsewhere(_waiting(session, state), session.path)


def _where(loc: Any, path: str) -> str:
    """``:37`` in the mission's own file, ``homing.orc:26`` in another."""
    name = Path(loc.file or path).name
    return f":{loc.line}" if name == Path(path).name else f"{name}:{loc.line}"


def tasks_in_state(session: Any, state: int | None) -> list[tuple[str, int, int]]:
    """``(task, site, phase)`` of every Robot-Task instance active in ``state`` (from the
    automaton's labels: right from the instant the task starts)."""
    automaton = session.automaton
    if state is None or not automaton.labels or not 0 <= state < len(automaton.labels):
        return []
    phases: dict[tuple[str, int], int] = {}
    for label in automaton.labels[state]:
        phase = getattr(label, "phase", None)
        if hasattr(label, "site") and hasattr(label, "task"):
            key = (label.task, label.site)
            phases[key] = max(phases.get(key, 1), int(phase) if phase is not None else 1)
    return [(task, site, phase) for (task, site), phase in sorted(phases.items(),
                                                                  key=lambda kv: kv[0][1])]


def run_site_lines(session: Any, state: int | None) -> list[int]:
    """Lines of the ``run`` statements of the Robot-Tasks active in ``state`` in the
    mission's file."""
    return _in_file([loc for _, loc in running_sites(session, state)], session.path)


MAX_WAITING = 4
"""Locations shown in the status line (the Source tab, ``o``, shows them all)."""


def where_text(session: Any, state: int | None, status: str = Status.RUNNING,
               limit: int = MAX_WAITING) -> str:
    """``waiting at arm_recovery.orc:58, 77, homing.orc:26 (running TrackPID at :48)`` (or
    the status once the mission ended); past ``limit`` locations, ``… +N``. The
    running Robot-Tasks come first when the list is cut, so a small terminal shows them."""
    if status in (Status.DONE, Status.FAILED, Status.ABORTED):
        return f"the mission has ended: {status}"
    waiting = _waiting(session, state)
    if not waiting:
        return "starting" if state is None else "reacting"
    name = Path(session.path).name
    own = [str(line) for line in waiting_lines(session, state)]
    others = elsewhere(waiting, session.path)
    cut = max(0, len(own) + len(others) - limit)
    if cut:
        own, others = own[:limit], others[:max(0, limit - len(own))]
    parts = ([f"{name}:{', '.join(own)}"] if own else []) + others
    text = f"waiting at {', '.join(parts)}" + (f" … +{cut}" if cut else "")
    running = running_sites(session, state)
    if running:
        tasks = ", ".join(f"{task} at {_where(loc, session.path)}" for task, loc in running)
        text = f"running {tasks}; {text}" if cut else f"{text} (running {tasks})"
    return text


def running_sites(session: Any, state: int | None) -> list[tuple[str, Any]]:
    """``(task, its run statement's location)`` of the Robot-Tasks active in ``state``."""
    automaton = session.automaton
    if state is None or not automaton.labels or not 0 <= state < len(automaton.labels):
        return []
    numbers = {getattr(label, "site", None) for label in automaton.labels[state]
               if not isinstance(label, tuple)}
    return [(site.task, site.site.stmt.loc) for site in session.run.plan.sites
            if site.number in numbers]


def _speed(session: Any, meter: SpeedMeter) -> tuple[str, str]:
    factor = session.pace.factor
    requested = "max" if factor is None else "paused" if factor == 0 else f"{factor:g}×"
    actual = meter.actual
    shown = "—" if actual is None or factor == 0 else f"{actual:.2f}×"
    lag = ""
    if factor not in (None, 0) and actual is not None and actual < LAG_RATIO * factor:
        lag = f"  [b red]lagging: {actual:.2f}× of the {factor:g}× asked[/]"
    return f"speed {requested} (actual {shown})", lag


def status_text(session: Any, update: LiveUpdate | None, meter: SpeedMeter,
                limit: int = MAX_WAITING) -> str:
    """Two lines: time/progress/speed, then where the mission waits (Rich markup; at most
    ``limit`` locations)."""
    horizon_s = session.run.until_ns / 1e9
    if update is None:
        return (f"mission {session.mission}: starting at {session.pace.label}   horizon "
                f"{horizon_s:g} s\n{where_text(session, None, limit=limit)}")
    t_s = update.time_ns / 1e9
    share = min(1.0, t_s / horizon_s) if horizon_s else 0.0
    bar = "█" * round(share * 10) + "░" * (10 - round(share * 10))
    speed, lag = _speed(session, meter)
    paused = "  [b reverse] PAUSED [/]" if session.pace.paused else ""
    held = f"  held: {', '.join(update.held)}" if update.held else ""
    return (f"t = {t_s:.3f} s of {horizon_s:g} s {bar} {share:.0%}   {speed}{paused}{lag}\n"
            f"{where_text(session, update.state, update.status, limit)}{held}")


def rta_text(session: Any, tasks: list[tuple[str, int, int]]) -> str:
    """Each running Robot-Task's RTA (RR-1801 §3.4): its three phases, the current one
    marked, its observers and exceptions with their types."""
    if not tasks:
        return "no Robot-Task is running: the RTA of each one shows here while it runs"
    sites = {site.number: site for site in session.run.plan.sites}
    blocks = []
    for task, number, phase in tasks:
        site = sites.get(number)
        lines = [f"[b]{task}[/b] (site {number}): phase {phase}, "
                 f"{_PHASE_TEXT.get(phase, Phase(phase).word)}"]
        for n in (1, 2, 3):
            mark = "▶" if n == phase else " "
            lines.append(f"  {mark} {n} {_PHASE_TEXT[n]}")
        if site is not None:
            lines.append(f"  modules: {', '.join(m.split('.', 1)[-1] for m in site.modules)}")
            if site.measuring:
                lines.append("  measuring: " + ", ".join(m.split(".", 1)[-1]
                                                         for m in site.measuring))
            for exception in site.site.robottask.exceptions:
                kind = exception.type.number
                adjust = site.adjustments.get(exception.name)
                what = (f"adjust {adjust.module.split('.', 1)[-1]}.{adjust.param} := "
                        f"{adjust.value}" if adjust else
                        {2: "abort the task", 3: "fatal"}.get(kind, ""))
                lines.append(f"  exception {exception.name} from {exception.source.func}: "
                             f"type {kind}, {what}")
        blocks.append("\n".join(lines))
    return "\n\n".join(blocks)


def tcs_rows(session: Any, tasks: list[tuple[str, int, int]], loads: dict[str, float],
             misses: dict[str, int]) -> list[tuple[str, ...]]:
    """Rows ``(module, processor, T ms, C ms, priority, active, misses)`` of the TCS, the
    running tasks' modules first, then one row per processor with its load."""
    running = {module for site in session.run.plan.sites
               if any(site.number == number for _, number, _ in tasks) for module in site.modules}
    modules = sorted(session.run.plan.tcs.module_tasks,
                     key=lambda m: (m.name not in running, m.name))
    rows: list[tuple[str, ...]] = [(m.name, m.processor, f"{m.period_ns / 1e6:g}", f"{m.wcet_ns / 1e6:g}",
             str(m.priority), "yes" if m.name in running else "", str(misses.get(m.name, 0)))
            for m in modules]
    rows += [(f"{name} load", name, "", "", "", f"{load:.1%}", "")
             for name, load in sorted(loads.items())]
    return rows
