"""File-level checks: types, Robot-Tasks, properties and assumptions."""

from __future__ import annotations

from orccad_app.lang import diagnose, parse
from tests.lang import examples


def messages(text: str) -> list[str]:
    return [e.message for e in diagnose(parse(text, "d.orc"))]


def test_reference_robottask_checks():
    assert messages("robot arm : arm3dof;\n" + examples.TRACK_PID) == []


def test_unknown_types_get_a_suggestion():
    assert messages("input B : flaot;") == ["unknown type 'flaot'; did you mean 'float'?"]
    assert messages("mission M { var x : text := 1; }") == [
        "unknown type 'text' (one of bool, duration, float, int, string, vector)"]
    assert messages("robot a : k; robottask T(p: matrix) on a { }") == [
        "unknown type 'matrix' (one of bool, duration, float, int, string, vector)"]
    assert messages("mission M { signal S : foo { } }") == [
        "unknown type 'foo' (one of bool, duration, float, int, string, vector)"]


def test_robottask_names():
    text = """robot arm : k;
robottask T(kp: float = 1.0, kp: float) on arm {
    module m : k period 1 ms;
    module m : k;
    law pid(kp = kp, kv = kv);
    connect m.x -> n.y;
    connect arm.q -> m.q;
    exception E from obs : abort;
    exception E from m : adjust z.kp = kp;
}
"""
    assert messages(text) == [
        "duplicate parameter 'kp'", "duplicate module 'm'", "duplicate exception 'E'",
        "unknown module 'n' in robottask 'T'", "unknown module 'z' in robottask 'T'",
        "unknown name 'kv' in robottask 'T'"]


def test_robottask_robot_must_be_declared():
    assert messages("robottask T() on rob { }") == [
        "unknown robot 'rob' (declare it with 'robot rob : TYPE;')"]


def test_parameter_defaults_are_constants():
    assert messages("robot a : k; robottask T(x: float = y) on a { }") == [
        "unknown name 'y' in the default of 'x'"]


def test_duplicate_robottasks():
    assert messages("robot a : k; robottask T() on a { } robottask T() on a { }") == [
        "duplicate robottask 'T'"]


def test_reference_properties_check():
    assert messages(examples.WHOLE_FILE) == []


def test_property_errors():
    base = examples.WHOLE_FILE
    assert messages(base + "property Nope.p: always true;") == [
        "property 'p' names unknown mission 'Nope'"]
    assert messages(base + "property ABRO.q: always (Z -> once A);") == [
        "unknown signal 'Z' in property 'q'"]
    assert messages(base + "property ArmDemo.r: eventually ended(Park);") == [
        "unknown Robot-Task 'Park' in property 'r'"]
    assert messages(base + "property ArmDemo.s: never raised(Boom);") == [
        "no Robot-Task can raise 'Boom'"]
    assert messages(base + "property ABRO.o_needs_a: true;") == [
        "duplicate property 'o_needs_a'"]


def test_assumptions_and_unqualified_properties():
    base = examples.WHOLE_FILE
    assert messages(base + "assume ABRO.fair: always eventually A;") == []
    assert messages(base + "assume ABRO.bad: always eventually Q;") == [
        "unknown signal 'Q' in assumption 'bad'"]
    # an unqualified property applies to every mission: its signals must exist in all
    assert messages(base + "property sane: always (done -> not failed);") == []
    assert messages(base + "property o: always O;") == ["unknown signal 'O' in property 'o'"]
    assert messages(base + "property t: always (raised(TrackingLost) or raised(Timeout) "
                           "or raised(at_rest_timeout) or raised(JointLimit));") == []
