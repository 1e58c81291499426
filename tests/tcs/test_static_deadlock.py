"""Static deadlock analysis: cycles of blocking protocol ends, named module.port."""

from __future__ import annotations

import pytest

from orccad_app.diagnostics import OrccadError
from orccad_app.tcs import (TCS, ModuleTask, Port, check_deadlock_free, find_deadlock_cycles,
                            ms)


def _loop(forward: str, backward: str) -> TCS:
    tcs = TCS("loop")
    for name in ("a", "b"):
        tcs.add(ModuleTask(name, ms(10), ms(1), None, (Port("x", "in"), Port("y", "out"))))
    tcs.connect("a.y", "b.x", forward)
    tcs.connect("b.y", "a.x", backward)
    return tcs


def test_two_modules_waiting_for_each_other_form_a_cycle():
    cycles = find_deadlock_cycles(_loop("asyn/syn", "asyn/syn"))
    assert len(cycles) == 1
    assert set(cycles[0].ports) == {"a.x", "b.x"}
    assert set(cycles[0].modules) == {"a", "b"}
    with pytest.raises(OrccadError, match=r"potential deadlock in TCS 'loop': "
                                          r"a.x \(read, asyn/syn\) -> b.x \(read, asyn/syn\)"):
        check_deadlock_free(_loop("asyn/syn", "asyn/syn"))


def test_one_free_running_end_breaks_the_cycle():
    assert find_deadlock_cycles(_loop("asyn/syn", "asyn/asyn")) == []
    check_deadlock_free(_loop("asyn/synF", "syn/asyn"))


def test_synd_reads_wait_for_the_bus_not_for_the_producer():
    assert find_deadlock_cycles(_loop("asyn/synD", "asyn/synD")) == []
    assert len(find_deadlock_cycles(_loop("asyn/synDF", "asyn/synDF"))) == 1


def test_a_rendez_vous_pipeline_is_deadlock_free():
    tcs = TCS("pipe")
    tcs.add(ModuleTask("a", ms(10), ms(1), None, (Port("y", "out"),)))
    tcs.add(ModuleTask("b", ms(10), ms(1), None, (Port("x", "in"), Port("y", "out"))))
    tcs.add(ModuleTask("c", ms(10), ms(1), None, (Port("x", "in"),)))
    tcs.connect("a.y", "b.x", "syn/syn")
    tcs.connect("b.y", "c.x", "syn/syn")
    assert find_deadlock_cycles(tcs) == []


def test_producer_ends_take_part_in_cycles():
    # a writes to b with syn/asyn (a may wait for b's read) and reads b's output with
    # asyn/synF (a waits for b's write): b may be stuck writing to a while a waits to write.
    tcs = TCS("mixed")
    tcs.add(ModuleTask("a", ms(10), ms(1), None, (Port("x", "in"), Port("y", "out"))))
    tcs.add(ModuleTask("b", ms(10), ms(1), None, (Port("x", "in"), Port("y", "out"))))
    tcs.connect("a.y", "b.x", "synF/asyn")
    tcs.connect("b.y", "a.x", "synF/asyn")
    cycles = find_deadlock_cycles(tcs)
    assert len(cycles) == 1
    assert set(cycles[0].ports) == {"a.y", "b.y"}
    assert "a.y (write, synF/asyn)" in cycles[0].describe()
