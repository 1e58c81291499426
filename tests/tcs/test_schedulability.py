"""Static analysis: per-processor utilization and fixed-priority response times."""

from __future__ import annotations

import pytest

from orccad_app.tcs import ModuleTask, ms, response_time_analysis, us, utilization


def _set(processor="cpu0"):
    return [ModuleTask("a", ms(7), ms(2), priority=1, processor=processor),
            ModuleTask("b", ms(12), ms(3), priority=2, processor=processor),
            ModuleTask("c", ms(20), ms(5), priority=3, processor=processor)]


def test_utilization_per_processor():
    tasks = _set() + [ModuleTask("d", ms(10), ms(4), processor="cpu1")]
    loads = utilization(tasks)
    assert list(loads) == ["cpu0", "cpu1"]
    assert loads["cpu0"] == pytest.approx(2 / 7 + 3 / 12 + 5 / 20)
    assert loads["cpu1"] == pytest.approx(0.4)


def test_response_times_of_the_textbook_iteration():
    result = response_time_analysis(_set())
    # a: 2; b: 3 + ceil(5/7)*2 = 5; c: 5 + ceil(12/7)*2 + ceil(12/12)*3 = 12.
    assert {name: r.response_ns for name, r in result.items()} == {
        "a": ms(2), "b": ms(5), "c": ms(12)}
    assert all(r.schedulable for r in result.values())


def test_context_switches_and_blocking_add_to_the_response():
    result = response_time_analysis(_set(), context_switch_ns=us(100),
                                     blocking_ns={"b": ms(1)})
    assert result["a"].response_ns == us(2200)
    # b: 1 + 3.2 + ceil(R/7) * 2.2 -> 6.4
    assert result["b"].response_ns == us(6400)


def test_processors_are_analysed_separately():
    tasks = _set("cpu0") + [ModuleTask("x", ms(5), ms(4), priority=1, processor="cpu1")]
    result = response_time_analysis(tasks)
    assert result["a"].response_ns == ms(2)
    assert result["x"].response_ns == ms(4)


def test_an_overloaded_task_is_unschedulable():
    tasks = [ModuleTask("a", ms(4), ms(3), priority=1),
             ModuleTask("b", ms(6), ms(2), priority=2)]
    result = response_time_analysis(tasks)
    assert result["a"].schedulable
    assert not result["b"].schedulable and result["b"].response_ns is None


def test_equal_priorities_interfere_both_ways():
    tasks = [ModuleTask("a", ms(10), ms(2), priority=1),
             ModuleTask("b", ms(10), ms(3), priority=1)]
    result = response_time_analysis(tasks)
    assert result["a"].response_ns == ms(5) and result["b"].response_ns == ms(5)
