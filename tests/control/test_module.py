"""Ports, timings and the module-kind base."""

import pytest

from orccad_app.control.errors import ControlError, DimensionMismatch, InvalidParameter
from orccad_app.control.module import (
    ModuleContext,
    ModuleInstance,
    ModuleKind,
    ParamSpec,
    PortSpec,
    Timing,
)


class Gain(ModuleKind):
    """A toy kind: y = k * u."""

    name = "gain"
    ports = (PortSpec("u", "in", "float"), PortSpec("y", "out", "float"))
    params = (ParamSpec("k", "float", 1.0, minimum=0.0),)

    def _instantiate(self, values, context):
        return GainInstance(self, values, self.ports)


class GainInstance(ModuleInstance):
    def compute(self, t_s, inputs):
        return {"y": self.params["k"] * inputs["u"]}


def test_port_spec_validates_direction_type_and_dim():
    with pytest.raises(ControlError, match="direction must be 'in' or 'out', got 'both'"):
        PortSpec("x", "both", "vector")
    with pytest.raises(ControlError, match="type must be one of .*got 'matrix'"):
        PortSpec("x", "in", "matrix")
    with pytest.raises(ControlError, match="dim 3 needs a vector type"):
        PortSpec("x", "in", "float", 3)
    port = PortSpec("q", "in", "vector").with_dim(3)
    assert port.dim == 3
    port.check_value([0.0, 1.0, 2.0])
    with pytest.raises(DimensionMismatch, match=r"expects a vector of 3, got shape \(2,\)"):
        port.check_value([0.0, 1.0])


def test_timing_is_in_integer_nanoseconds():
    assert Timing.from_ms(2.0, 0.3) == Timing(2_000_000, 300_000)
    assert Timing.from_ms(1.0, 0.5, 0.2).bcet_ns == 200_000
    with pytest.raises(ControlError, match="period_ns must be a positive integer, got 0"):
        Timing(0, 1)
    with pytest.raises(ControlError, match="bcet_ns must be in"):
        Timing(10, 5, 6)


def test_create_validates_parameters_and_set_param_retunes():
    kind = Gain()
    assert not kind.is_observer and kind.event_ports == ()
    instance = kind.create({"k": 2.0}, ModuleContext())
    instance.init()
    assert instance.compute(0.0, {"u": 3.0}) == {"y": 6.0}
    instance.set_param("k", 0.5)
    assert instance.compute(0.001, {"u": 3.0}) == {"y": 1.5}
    with pytest.raises(InvalidParameter, match="gain: k must be >= 0, got -1.0"):
        instance.set_param("k", -1.0)
    with pytest.raises(InvalidParameter, match="no parameter 'kk' .*did you mean 'k'"):
        instance.set_param("kk", 1.0)
    with pytest.raises(InvalidParameter, match="gain has no parameter 'g'"):
        kind.create({"g": 1.0}, ModuleContext())


def test_port_lookup_and_sources():
    kind = Gain()
    assert kind.port("u").direction == "in"
    with pytest.raises(ControlError, match="no port 'v'"):
        kind.port("v")
    assert kind.sources({}) == {"u": "u"}


def test_task_time_counts_from_the_first_job_after_init():
    instance = Gain().create({}, ModuleContext())
    instance.init()
    assert instance.task_time(10.0) == 0.0
    assert instance.task_time(10.5) == pytest.approx(0.5)
    instance.init()
    assert instance.task_time(20.0) == 0.0
