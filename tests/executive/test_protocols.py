"""The 8 protocols of docs/design.md (*The 8 port-synchronization protocols*), one test per row: who blocks when, and what is read.

Scenario "fast producer" unless stated: P (period 4 ms) -> C (period 10 ms), both 1 ms of
execution on one processor, C at the higher priority. P writes 1, 2, 3, ... at the end of its
jobs (at 1, 5, 9, 13, 17 ms when nothing blocks it); C reads at its releases (0, 10, 20 ms).
"""

from __future__ import annotations

from orccad_app.executive import Bus
from orccad_app.tcs import us


def test_asyn_asyn_never_blocks_and_reads_the_last_value(run_pair):
    run = run_pair("asyn/asyn", 4, 10, until_ms=21)
    assert run.blocks() == []
    assert run.reads() == [(0.0, "0.0"), (10.0, 3), (20.0, 5)]


def test_syn_syn_is_a_rendez_vous_the_first_to_arrive_waits(run_pair):
    run = run_pair("syn/syn", 4, 10, until_ms=21)
    # C arrives first at 0 and waits for P's write at 1; then P arrives first at 5 and 13
    # and waits for C's reads at 10 and 20 (P skips its releases meanwhile).
    assert run.blocks() == [(0.0, "C", "read"), (5.0, "P", "write"), (13.0, "P", "write")]
    assert run.unblocks() == [(1.0, "C", "read", 1.0), (10.0, "P", "write", 5.0),
                              (20.0, "P", "write", 7.0)]
    assert run.reads() == [(1.0, 1), (10.0, 2), (20.0, 3)]
    assert run.sim.stats().tasks["P"].overruns == 2


def test_asyn_syn_reads_a_fresh_value_at_once_else_waits_for_the_next_write(run_pair):
    run = run_pair("asyn/syn", 4, 10, until_ms=21)
    # at 0 nothing was written: C waits for the write at 1; at 10 and 20 a value written
    # since the last read (3 at 9, 5 at 17) is taken at once.
    assert run.blocks() == [(0.0, "C", "read")]
    assert run.unblocks() == [(1.0, "C", "read", 1.0)]
    assert run.reads() == [(1.0, 1), (10.0, 3), (20.0, 5)]


def test_syn_asyn_producer_waits_unless_read_since_its_last_write(run_pair):
    run = run_pair("syn/asyn", 4, 10, until_ms=21)
    # write 1 at 2 follows C's read at 0: no wait. Write 2 at 5 has no read since: P waits
    # for C's read at 10, which gets 1 (nothing unread is overwritten) and lets 2 in.
    assert run.blocks() == [(5.0, "P", "write"), (13.0, "P", "write")]
    assert run.unblocks() == [(10.0, "P", "write", 5.0), (20.0, "P", "write", 7.0)]
    assert run.reads() == [(0.0, "0.0"), (10.0, 1), (20.0, 2)]


def test_asyn_synf_consumer_always_waits_for_the_next_write(run_pair):
    run = run_pair("asyn/synF", 4, 10, until_ms=21)
    # at 10 the value 3 written at 9 is not enough: C waits for the write at 13.
    assert run.blocks() == [(0.0, "C", "read"), (10.0, "C", "read"), (20.0, "C", "read")]
    assert run.unblocks() == [(1.0, "C", "read", 1.0), (13.0, "C", "read", 3.0)]
    assert run.reads() == [(1.0, 1), (13.0, 4)]


def test_synf_asyn_producer_always_waits_for_the_next_read(run_pair):
    run = run_pair("synF/asyn", 4, 10, until_ms=21)
    # even the first write (at 2, after C's read at 0) waits for the next read, at 10;
    # the read that releases P gets the value delivered before it.
    assert run.blocks() == [(2.0, "P", "write"), (13.0, "P", "write")]
    assert run.unblocks() == [(10.0, "P", "write", 8.0), (20.0, "P", "write", 7.0)]
    assert run.reads() == [(0.0, "0.0"), (10.0, "0.0"), (20.0, 1)]


def test_asyn_synd_request_and_reply_over_the_bus_bring_the_latest_value(run_pair):
    bus = Bus(transfer_ns=us(500), request_ns=us(250))
    run = run_pair("asyn/synD", 4, 10, until_ms=21, remote=True, bus=bus)
    # request 250 us + reply 500 us: C waits 750 us per read for the producer side's latest
    # value (0.0 at 0.25, 3 at 10.25, 5 at 20.25); writes cost no traffic.
    assert run.blocks() == [(0.0, "C", "read"), (10.0, "C", "read"), (20.0, "C", "read")]
    assert run.unblocks() == [(0.75, "C", "read", 0.75), (10.75, "C", "read", 0.75),
                              (20.75, "C", "read", 0.75)]
    assert run.reads() == [(0.75, "0.0"), (10.75, 3), (20.75, 5)]
    assert bus.stats.by_kind == {"data": 0, "request": 3, "reply": 3}


def test_asyn_synd_on_one_processor_answers_at_once(run_pair):
    run = run_pair("asyn/synD", 4, 10, until_ms=21)
    assert run.blocks() == []
    assert run.reads() == [(0.0, "0.0"), (10.0, 3), (20.0, 5)]


def test_asyn_syndf_reply_carries_the_first_write_after_the_request(run_pair):
    bus = Bus(transfer_ns=us(500), request_ns=us(250))
    run = run_pair("asyn/synDF", 4, 10, until_ms=21, remote=True, bus=bus)
    # request arrives at 0.25 / 10.25 / 20.25; the next writes are at 1 and 13 (value 4),
    # replies take 500 us; the write at 21 is beyond the run.
    assert run.blocks() == [(0.0, "C", "read"), (10.0, "C", "read"), (20.0, "C", "read")]
    assert run.unblocks() == [(1.5, "C", "read", 1.5), (13.5, "C", "read", 3.5)]
    assert run.reads() == [(1.5, 1), (13.5, 4)]
    assert bus.stats.by_kind == {"data": 0, "request": 3, "reply": 2}


def test_syn_syn_across_processors_both_wait_for_the_transfer(run_pair):
    bus = Bus(transfer_ns=us(500))
    run = run_pair("syn/syn", 4, 10, until_ms=11, remote=True, bus=bus)
    # C (cpu1) waits from 0; P (cpu0) meets it at 1 and both go on when the value lands at
    # 1.5. P's write at 5 waits for C's read at 10, then the transfer (until 10.5).
    assert run.blocks() == [(0.0, "C", "read"), (1.0, "P", "write"), (5.0, "P", "write"),
                            (10.0, "C", "read")]
    assert run.unblocks() == [(1.5, "C", "read", 1.5), (1.5, "P", "write", 0.5),
                              (10.5, "C", "read", 0.5), (10.5, "P", "write", 5.5)]
    assert run.reads() == [(1.5, 1), (10.5, 2)]
    assert bus.stats.by_kind["data"] == 2


def test_asyn_asyn_across_processors_sends_every_write(run_pair):
    bus = Bus(transfer_ns=us(100))
    run = run_pair("asyn/asyn", 4, 10, until_ms=21, remote=True, bus=bus)
    # P runs on cpu0 alone: writes at 1, 5, 9, 13, 17 -> 5 data messages, visible 100 us later.
    assert bus.stats.by_kind == {"data": 5, "request": 0, "reply": 0}
    assert run.reads() == [(0.0, "0.0"), (10.0, 3), (20.0, 5)]
