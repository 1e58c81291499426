"""Processors: fixed-priority preemption, EDF ordering, context-switch overhead, load."""

from __future__ import annotations

from orccad_app.executive import EventLog, Processor, Simulation
from orccad_app.tcs import TCS, ModuleTask, ms, us


def _run(tasks, until_ns, **processor):
    log = EventLog()
    sim = Simulation(TCS("s", tasks), processors=[Processor("cpu0", **processor)],
                     observers=[log])
    sim.activate()
    stats = sim.run(until_ns)
    timeline = [(e[0], e[1], e[2]) for e in log.events
                if e[0] in ("on_start", "on_preempt", "on_resume", "on_compute_end")]
    return stats, timeline


def test_fixed_priority_preempts_the_lower_priority_job():
    low = ModuleTask("low", ms(10), ms(4), priority=2)
    high = ModuleTask("high", ms(10), ms(2), priority=1, offset_ns=ms(1))
    stats, timeline = _run([low, high], ms(9))
    assert timeline == [
        ("on_start", 0, "low"), ("on_preempt", ms(1), "low"), ("on_start", ms(1), "high"),
        ("on_compute_end", ms(3), "high"), ("on_resume", ms(3), "low"),
        ("on_compute_end", ms(6), "low"),
    ]
    assert stats.tasks["low"].response_max_ns == ms(6)
    assert stats.tasks["low"].preemptions == 1
    assert stats.processors["cpu0"].busy_ns == ms(6)


def test_equal_priorities_do_not_preempt_each_other():
    first = ModuleTask("first", ms(10), ms(4), priority=1)
    second = ModuleTask("second", ms(10), ms(2), priority=1, offset_ns=ms(1))
    stats, timeline = _run([first, second], ms(9))
    assert timeline[:3] == [("on_start", 0, "first"), ("on_compute_end", ms(4), "first"),
                            ("on_start", ms(4), "second")]
    assert stats.tasks["first"].preemptions == 0


def test_edf_runs_the_earliest_deadline_first_whatever_the_priority():
    urgent = ModuleTask("urgent", ms(20), ms(3), priority=2, deadline_ns=ms(5))
    relaxed = ModuleTask("relaxed", ms(20), ms(3), priority=1, deadline_ns=ms(20))
    _, fp = _run([urgent, relaxed], ms(10))
    _, edf = _run([urgent, relaxed], ms(10), scheduler="edf")
    assert [e[2] for e in fp if e[0] == "on_start"] == ["relaxed", "urgent"]
    assert [e[2] for e in edf if e[0] == "on_start"] == ["urgent", "relaxed"]


def test_edf_preempts_when_a_later_release_has_an_earlier_deadline():
    long = ModuleTask("long", ms(50), ms(6), priority=1, deadline_ns=ms(50))
    short = ModuleTask("short", ms(50), ms(1), priority=2, deadline_ns=ms(2),
                       offset_ns=ms(2))
    stats, timeline = _run([long, short], ms(10), scheduler="edf")
    assert ("on_preempt", ms(2), "long") in timeline
    assert stats.tasks["short"].response_max_ns == ms(1)
    assert stats.tasks["long"].response_max_ns == ms(7)


def test_context_switch_overhead_is_paid_at_each_dispatch_and_resumption():
    low = ModuleTask("low", ms(10), ms(4), priority=2)
    high = ModuleTask("high", ms(10), ms(2), priority=1, offset_ns=ms(1))
    stats, timeline = _run([low, high], ms(9), context_switch_ns=us(100))
    # low: 0.1 switch + 1 ms run, preempted at 1; high: 0.1 + 2 -> 3.1;
    # low resumes with 3.1 ms left + 0.1 switch -> 6.3.
    assert ("on_compute_end", us(3100), "high") in timeline
    assert ("on_compute_end", us(6300), "low") in timeline
    assert stats.tasks["low"].response_max_ns == us(6300)
    cpu = stats.processors["cpu0"]
    assert cpu.context_switches == 3
    assert cpu.busy_ns == us(6300)


def test_processor_load_is_the_busy_fraction():
    task = ModuleTask("t", ms(4), ms(1))
    stats, _ = _run([task], ms(400))
    assert stats.processors["cpu0"].load == 0.25
    assert stats.tasks["t"].completed == 100
    assert stats.tasks["t"].response_mean_ns == ms(1)
