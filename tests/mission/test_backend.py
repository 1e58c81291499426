"""Where a Module-Task's job runs is the run's backend (``mission/backend.py``): MissionRun
takes it as a constructor argument and goes through it for every activation, kill, port reset
and input, and around its events."""

from __future__ import annotations

from contextlib import contextmanager

from orccad_app.executive import EventLog
from orccad_app.mission.backend import InProcess
from orccad_app.mission.injection import parse_injection
from orccad_app.mission.plan import plan_mission
from orccad_app.mission.run import MissionRun
from orccad_app.pipeline import load, select_mission

from tests.mission.conftest import ROOT


def _plan():
    source = load(str(ROOT / "missions" / "arm_recovery.orc"))
    return plan_mission(source, select_mission(source, None))


class _Recording(InProcess):
    """The in-process backend, every call the run makes to it recorded."""

    def __init__(self) -> None:
        super().__init__()
        self.calls: list[tuple] = []

    def activate(self, modules, at_ns):
        self.calls.append(("activate", tuple(modules), at_ns))
        super().activate(modules, at_ns)

    def kill(self, modules, at_ns):
        self.calls.append(("kill", tuple(modules), at_ns))
        super().kill(modules, at_ns)

    def reset_ports(self, modules, at_ns):
        self.calls.append(("reset_ports", tuple(modules), at_ns))
        super().reset_ports(modules, at_ns)

    def take_input(self, name, value, at_ns):
        self.calls.append(("input", name, at_ns))
        return False

    @contextmanager
    def running(self):
        self.calls.append(("running",))
        yield
        self.calls.append(("ran",))

    def finish(self, result):
        self.calls.append(("finish", result.status))
        return result


def test_the_run_goes_through_its_backend_and_runs_as_in_process():
    inject = [parse_injection("TrackPID.TrackingLost@2.5")]
    default_log, recorded_log = EventLog(), EventLog()
    expected = MissionRun(_plan(), observers=[default_log], injections=inject,
                          until_ns=6_000_000_000).run()
    backend = _Recording()
    got = MissionRun(_plan(), observers=[recorded_log], injections=inject,
                     until_ns=6_000_000_000, backend=backend).run()
    assert default_log.events == recorded_log.events  # the same run, event for event
    assert (got.status, got.sim_time_ns) == (expected.status, expected.sim_time_ns)
    calls = backend.calls
    assert calls[0] == ("running",) and calls[-2:] == [("ran",), ("finish", got.status)]
    assert ("input", "TrackPID.TrackingLost", 2_500_000_000) in calls
    assert any(c[0] == "activate" and c[2] == 0 for c in calls)  # Home starts at 0
    assert any(c[0] == "kill" and c[2] == 2_500_000_000 for c in calls)  # TrackPID lost
    assert any(c[0] == "reset_ports" for c in calls)  # each start: fresh ports


class _OwnClock(InProcess):
    """A backend whose automaton keeps its own clock: no tick from the run, inputs taken."""

    reacts_on_ticks = False
    input_lead_ns = 1_000_000

    def __init__(self) -> None:
        super().__init__()
        self.taken: list[tuple[str, int, int]] = []
        self._kernel = None

    def attach(self, run, simulation):
        super().attach(run, simulation)
        self._kernel = run.kernel

    def take_input(self, name, value, at_ns):
        self.taken.append((name, at_ns, self._kernel.now))
        return True


def test_a_backend_with_its_own_clock_gets_the_inputs_ahead_and_no_tick():
    backend = _OwnClock()
    reactions = []

    class Reactions:
        def on_reaction(self, now, inputs, outputs, status):
            reactions.append(now)

    MissionRun(_plan(), injections=[parse_injection("TrackPID.TrackingLost@0.5")],
               until_ns=1_000_000_000, backend=backend, observers=[Reactions()]).run()
    assert backend.taken == [("TrackPID.TrackingLost", 500_000_000, 499_000_000)]
    assert reactions == []  # the run itself never reacted: the backend's automaton does
