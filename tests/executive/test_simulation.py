"""Simulation control: activate/kill at instants, parameter changes, signals, overruns."""

from __future__ import annotations

import pytest

from orccad_app.diagnostics import OrccadError
from orccad_app.executive import ComputeError, EventLog, Observer, Simulation
from orccad_app.tcs import TCS, ModuleTask, Port, ms


class Gain:
    """Writes ``gain * t`` on ``y``; ``init`` resets; ``set_param('gain', g)`` retunes."""

    def __init__(self) -> None:
        self.gain = 1.0
        self.inits = 0

    def init(self) -> None:
        self.inits += 1

    def set_param(self, name, value):
        if name != "gain":
            raise KeyError(name)
        self.gain = value

    def compute(self, t_s, inputs):
        return {"y": self.gain * t_s}


class Threshold:
    """Emits ``alarm`` (an event port) when its input exceeds 0.02."""

    def compute(self, t_s, inputs):
        return {"alarm": inputs["u"] > 0.02}


def _tcs():
    tcs = TCS("ctl")
    tcs.add(ModuleTask("gen", ms(5), ms(1), Gain(), (Port("y", "out"),)))
    tcs.add(ModuleTask("obs", ms(5), ms(1), Threshold(),
                       (Port("u", "in"), Port("alarm", "out", "event")), priority=2))
    tcs.connect("gen.y", "obs.u", "asyn/asyn")
    return tcs


def test_activate_and_kill_at_given_instants():
    log = EventLog()
    sim = Simulation(_tcs(), observers=[log])
    sim.activate(["gen"], at_ns=ms(10))
    sim.kill("gen", at_ns=ms(30))
    stats = sim.run(ms(50))
    releases = [e[1] for e in log.events if e[0] == "on_release" and e[2] == "gen"]
    assert releases == [ms(10), ms(15), ms(20), ms(25)]  # a kill at 30 prevents the release
    assert stats.tasks["obs"].released == 0
    assert sim.tasks["gen"].task.compute.inits == 1
    assert [e[:3] for e in log.events if e[0] in ("on_activate", "on_kill")] == [
        ("on_activate", ms(10), "gen"), ("on_kill", ms(30), "gen")]


def test_killing_aborts_the_running_job_and_frees_the_processor():
    tcs = TCS("k", [ModuleTask("long", ms(10), ms(6), priority=1),
                    ModuleTask("other", ms(10), ms(1), priority=2)])
    log = EventLog()
    sim = Simulation(tcs, observers=[log])
    sim.activate()
    sim.kill("long", at_ns=ms(2))
    stats = sim.run(ms(10))
    assert stats.tasks["long"].aborted == 1 and stats.tasks["long"].completed == 0
    assert ("on_start", ms(2), "other", 0, "cpu0") in log.events
    assert stats.processors["cpu0"].busy_ns == ms(3)


def test_set_param_changes_the_outputs_from_that_instant():
    log = EventLog()
    sim = Simulation(_tcs(), observers=[log])
    sim.activate()
    sim.set_param("gen", "gain", 10.0, at_ns=ms(12))
    sim.run(ms(21))
    writes = [(e[1], float(e[4])) for e in log.events if e[0] == "on_write" and e[2] == "gen"]
    assert writes == [(ms(1), 0.0), (ms(6), 0.005), (ms(11), 0.01), (ms(16), 0.15)]
    assert ("on_param", ms(12), "gen", "gain", "10.0") in log.events


def test_event_ports_surface_signals_with_their_time_and_reactions_apply_at_once():
    sim = Simulation(_tcs())
    signals = []

    def react(t_ns, name, value):
        signals.append((t_ns, name, value))
        sim.kill(["gen", "obs"])  # zero-time reaction, like an automaton's output

    sim.on_signal(react)
    sim.activate()
    stats = sim.run(ms(100))
    # gen writes 0.025 at 26 ms (job of 25 ms); obs reads it at 30 ms and emits at 32 ms.
    assert signals == [(ms(32), "obs.alarm", True)]
    assert stats.tasks["gen"].released == 7  # 0, 5, ..., 30: the kill at 32 stops it
    assert not sim.tasks["obs"].active


def test_posted_signals_reach_observers():
    class Seen(Observer):
        def __init__(self):
            self.signals = []

        def on_signal(self, t_ns, name, value):
            self.signals.append((t_ns, name, value))

    seen = Seen()
    sim = Simulation(_tcs(), observers=[seen])
    sim.post_signal("operator_stop", at_ns=ms(7))
    sim.run(ms(10))
    assert seen.signals == [(ms(7), "operator_stop", True)]


def test_a_job_still_running_at_its_next_release_skips_it_and_misses_its_deadline():
    tcs = TCS("o", [ModuleTask("slow", ms(10), ms(4), priority=2),
                    ModuleTask("hog", ms(30), ms(9), priority=1, offset_ns=ms(1))])
    log = EventLog()
    sim = Simulation(tcs, observers=[log])
    sim.activate()
    stats = sim.run(ms(20))
    # slow runs 0-1, is preempted by hog (1-10), its release at 10 is skipped, ends at 13.
    assert ("on_overrun", ms(10), "slow", 0) in log.events
    slow = stats.tasks["slow"]
    assert (slow.overruns, slow.late, slow.response_max_ns) == (1, 1, ms(13))
    assert ("on_finish", ms(13), "slow", 0, ms(13), True) in log.events


def test_run_continues_across_segments():
    sim = Simulation(_tcs())
    sim.activate()
    sim.run(ms(12))
    stats = sim.run(ms(40))
    assert stats.time_ns == ms(40) and stats.tasks["gen"].released == 8


def test_bad_commands_and_failing_compute_raise_orccad_errors():
    sim = Simulation(_tcs())
    with pytest.raises(OrccadError, match="unknown module-task 'nope'"):
        sim.activate("nope")
    with pytest.raises(OrccadError, match="run until"):
        sim.run(-1)

    class Broken:
        def compute(self, t_s, inputs):
            raise ZeroDivisionError("boom")

    tcs = TCS("b", [ModuleTask("bad", ms(5), ms(1), Broken())])
    sim = Simulation(tcs)
    sim.activate()
    with pytest.raises(ComputeError, match="module-task 'bad': compute raised "
                                           "ZeroDivisionError: boom"):
        sim.run(ms(10))


def test_observers_only_get_the_hooks_they_override():
    class Finishes(Observer):
        def __init__(self):
            self.count = 0

        def on_finish(self, t_ns, module, job, response_ns, missed):
            self.count += 1

    finishes = Finishes()
    sim = Simulation(_tcs(), observers=[finishes])
    assert sim.hooks.on_release == [] and len(sim.hooks.on_finish) == 1
    sim.activate()
    sim.run(ms(20))
    assert finishes.count == 8


def test_paced_run_follows_the_wall_clock_and_gives_the_same_result():
    import time

    fast = Simulation(_tcs())
    fast.activate()
    expected = fast.run(ms(60)).tasks["gen"].completed
    paced = Simulation(_tcs())
    paced.activate()
    start = time.perf_counter()
    stats = paced.run(ms(60), realtime=2.0)  # 60 ms of simulated time in about 30 ms
    elapsed = time.perf_counter() - start
    assert elapsed >= 0.029
    assert stats.tasks["gen"].completed == expected
    assert paced.lateness_max_s >= 0.0
