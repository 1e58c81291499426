"""The discrete-event kernel: ordering, cancellation, run segments, seeded streams."""

from __future__ import annotations

import numpy as np
import pytest

from orccad_app.diagnostics import OrccadError
from orccad_app.executive import EventClass, Kernel


def test_events_run_by_time_then_class_then_insertion():
    kernel = Kernel()
    order = []
    kernel.schedule(5, EventClass.DISPATCH, order.append, "dispatch@5")
    kernel.schedule(5, EventClass.RELEASE, order.append, "release@5 first")
    kernel.schedule(5, EventClass.RELEASE, order.append, "release@5 second")
    kernel.schedule(5, EventClass.FINISH, order.append, "finish@5")
    kernel.schedule(3, EventClass.DISPATCH, order.append, "dispatch@3")
    kernel.run(10)
    assert order == ["dispatch@3", "finish@5", "release@5 first", "release@5 second",
                     "dispatch@5"]
    assert kernel.now == 10 and kernel.events_processed == 5


def test_a_deferred_event_runs_where_a_dispatch_event_of_its_instant_would():
    """Kernel.defer is schedule(now, DISPATCH) without the heap: after every other event of
    the instant (even one scheduled later, of an earlier class), before the next instant, in
    call order among deferred events, each taking a sequence number."""
    kernel = Kernel()
    order = []

    def at_5(_):
        seq = kernel._seq
        kernel.defer(order.append, "deferred first")
        assert kernel._seq == seq + 1
        kernel.schedule(5, EventClass.RELEASE, order.append, "release@5 scheduled after")
        kernel.defer(lambda _: (order.append("deferred second"),
                                kernel.schedule(5, EventClass.FINISH, order.append,
                                                "finish@5 from a deferred one")))
        kernel.defer(order.append, "deferred third")

    kernel.schedule(5, EventClass.CONTROL, at_5)
    kernel.schedule(6, EventClass.FINISH, order.append, "finish@6")
    kernel.run(10)
    assert order == ["release@5 scheduled after", "deferred first", "deferred second",
                     "finish@5 from a deferred one", "deferred third", "finish@6"]
    assert kernel.events_processed == 7


def test_a_deferred_event_survives_a_stop_and_counts_in_peek_and_run_instant():
    kernel = Kernel()
    order = []

    def at_2(_):
        kernel.defer(order.append, "deferred@2")
        kernel.stop()

    kernel.schedule(2, EventClass.CONTROL, at_2)
    kernel.schedule(4, EventClass.RELEASE, order.append, "release@4")
    kernel.run(10)
    assert order == [] and kernel.now == 2 and kernel.peek_ns() == 2
    assert kernel.run_instant() == 2 and order == ["deferred@2"] and kernel.now == 2
    kernel.run(10)
    assert order == ["deferred@2", "release@4"] and kernel.now == 10


def test_cancelled_events_do_not_run_and_until_is_exclusive():
    kernel = Kernel()
    seen = []
    entry = kernel.schedule(2, EventClass.FINISH, seen.append, "cancelled")
    kernel.schedule(4, EventClass.FINISH, seen.append, "at 4")
    kernel.schedule(6, EventClass.FINISH, seen.append, "at 6")
    kernel.cancel(entry)
    kernel.run(6)
    assert seen == ["at 4"] and kernel.now == 6
    assert kernel.peek_ns() == 6
    kernel.run(7)
    assert seen == ["at 4", "at 6"]


def test_events_cannot_be_scheduled_in_the_past():
    kernel = Kernel()
    kernel.run(100)
    with pytest.raises(OrccadError, match="in the past"):
        kernel.schedule(99, EventClass.FINISH, print)


def test_named_streams_depend_only_on_seed_and_name():
    a = Kernel(seed=42)
    b = Kernel(seed=42)
    b.stream("other").normal(size=10)  # creating another stream first changes nothing
    assert np.array_equal(a.stream("mt/x").integers(0, 1 << 30, 5),
                          b.stream("mt/x").integers(0, 1 << 30, 5))
    assert not np.array_equal(Kernel(seed=42).stream("mt/y").random(5),
                              Kernel(seed=42).stream("mt/x").random(5))
    assert not np.array_equal(Kernel(seed=43).stream("mt/x").random(5),
                              Kernel(seed=42).stream("mt/x").random(5))


def test_seed_must_be_a_non_negative_integer():
    with pytest.raises(OrccadError, match="seed"):
        Kernel(seed=-1)


def test_run_instant_processes_one_instant_and_keeps_the_clock_there():
    kernel = Kernel()
    seen = []
    kernel.schedule(3, EventClass.RELEASE, seen.append, "a")
    kernel.schedule(3, EventClass.FINISH, lambda _: kernel.schedule(3, EventClass.WAKE,
                                                                   seen.append, "woken"))
    kernel.schedule(8, EventClass.RELEASE, seen.append, "later")
    assert kernel.run_instant() == 3
    assert seen == ["woken", "a"] and kernel.now == 3
    assert kernel.run_instant() == 8 and kernel.run_instant() is None


def test_stop_returns_after_the_current_event_leaving_the_clock_there():
    kernel = Kernel()
    seen = []
    kernel.schedule(5, EventClass.CONTROL, lambda _: (seen.append(5), kernel.stop()))
    kernel.schedule(5, EventClass.RELEASE, seen.append, "later at 5")
    kernel.schedule(9, EventClass.CONTROL, seen.append, 9)
    kernel.run(100)
    assert (seen, kernel.now, kernel.stopped) == ([5], 5, True)
    kernel.run(100)  # a new run clears the request and goes on
    assert (seen, kernel.now) == ([5, "later at 5", 9], 100)
