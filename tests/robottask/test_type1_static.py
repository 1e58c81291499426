"""Type-1 updates checked when the file is loaded: the parameters an update sets and reads exist,
its value computes (functions, arity, ramp shape), a constant value (each end of a constant
ramp) is valid for its parameter, a computed one has the parameter's type and shape; module
parameters are read only by an ``adjust``. Each error is located at the offending part."""

from __future__ import annotations

import pytest

from orccad_app.diagnostics import OrccadError
from orccad_app.pipeline import load

ARM_PID = open("missions/arm_pid.orc", encoding="utf-8").read()
CLAUSE = "adjust ctrl.kp = 200.0"


def _load(tmp_path, value: str, old: str = CLAUSE):
    assert old in ARM_PID
    path = tmp_path / "m.orc"
    path.write_text(ARM_PID.replace(old, value), encoding="utf-8")
    return load(path)


def _error(tmp_path, value: str, old: str = CLAUSE) -> OrccadError:
    with pytest.raises(OrccadError) as caught:
        _load(tmp_path, value, old)
    return caught.value


def _column(text: str, fragment: str) -> int:
    line = next(line for line in text.splitlines() if "adjust" in line)
    return line.index(fragment) + 1


@pytest.mark.parametrize("clause, message, at", [
    ("adjust ctrl.kp = ctrl.kpp * 2.0", "has no parameter 'kpp' (did you mean 'kp'?)",
     "ctrl.kpp"),
    ("adjust ctrl.kpp = 2.0", "has no parameter 'kpp'", "ctrl.kpp"),
    ("adjust ctrl.kp = ctrlx.kp * 2.0", "unknown module 'ctrlx'", "ctrlx"),
    ("adjust ctrl.kp = foo(ctrl.kp)", "unknown function 'foo' in a type-1 update", "foo"),
    ("adjust ctrl.kp = min(ctrl.kp)", "min takes at least 2 arguments, got 1", "min"),
    ("adjust ctrl.kp = clip(ctrl.kp, 1.0)", "clip takes 3 arguments, got 2", "clip"),
    ("adjust ctrl.kp = ctrl.kp > 2.0", "not with '>'", "ctrl.kp >"),
    ("adjust ctrl.kp = ramp(1.0, 2.0)", "ramp needs duration", "ramp"),
    ("adjust ctrl.kp = ramp(1.0, 2.0, 1.0)", "a duration literal > 0", "1.0)"),
    ("adjust ctrl.kp = min(ramp(1.0, 2.0, 1 s), 3.0)", "is the whole value of an update",
     "ramp"),
    ("adjust ctrl.kp = ramp(100.0, -1.0, 1 s)", "kp must be > 0, got -1.0", "-1.0"),
    ("adjust ctrl.kp = -2.0", "kp must be > 0, got -2.0", "-2.0"),
    ("adjust ctrl.kp = ctrl.kp / 0.0", "kp must be finite, got inf", "ctrl.kp /"),
    ("adjust ctrl.kp = ctrl.kp * [1.0, 2.0]", "kp has 2 components, expected dim e = 3",
     "ctrl.kp *"),
    ("adjust ctrl.kp = ctrl.anti_windup * 2.0", "computes with numbers, got True",
     "ctrl.anti_windup"),
    ("adjust ctrl.anti_windup = ramp(0.0, 1.0, 1 s)", "a ramp moves a real parameter; "
                                                       "ctrl.anti_windup is a bool", "ramp"),
    ("adjust traj.omegaa = 1.0", "trajectory 'cosine') has no parameter 'omegaa' (did you "
                                 "mean 'omega'?); its parameters: q0, omega", "traj.omegaa"),
])
def test_a_bad_update_is_refused_where_it_is_wrong(tmp_path, clause, message, at):
    error = _error(tmp_path, clause)
    assert message in error.message
    text = ARM_PID.replace(CLAUSE, clause)
    line = next(i for i, line in enumerate(text.splitlines(), 1) if "adjust" in line)
    assert (error.location.line, error.location.col) == (line, _column(text, at))


def test_module_parameters_are_read_only_by_an_update(tmp_path):
    error = _error(tmp_path, "law pid(kp = ctrl.kv, ", "law pid(kp = kp, ")
    assert "'ctrl.kv' is a Module-Task parameter: only the value of a type-1 exception" in \
        error.message


@pytest.mark.parametrize("clause", [
    "adjust ctrl.kp = min(ctrl.kp * 1.5, 800.0)",
    "adjust ctrl.kp = ctrl.kp - 500.0",  # out of range at the nominal values: checked when applied
    "adjust ctrl.kp = clip(ctrl.kv * 20.0, 100.0, kp)",
    "adjust ctrl.kp = max(abs(ctrl.kp - 1000.0), [100.0, 200.0, 300.0])",
    "adjust ctrl.ki = ramp(0.0, 20.0, 1 s)",
    "adjust ctrl.kv = ramp(ctrl.kv, ctrl.kv * 2.0, 500 ms)",
    "adjust ctrl.anti_windup = false",
    "adjust traj.omega = traj.omega / 2.0",
])
def test_good_updates_load(tmp_path, clause):
    assert _load(tmp_path, clause).program.robottask("TrackPID") is not None


def test_a_constant_update_keeps_its_value_and_a_computed_one_its_form(tmp_path):
    from orccad_app.robottask.model import instantiate

    source = _load(tmp_path, "adjust ctrl.kp = min(ctrl.kp * 1.5, kp * 2.0)")
    task = next(t for t in source.program.robottasks if t.name == "TrackPID")
    instance = instantiate(task, {r.name: r for r in source.program.robots}, source.host)
    update = instance.adjustments["Saturated"]
    assert update.value is None and not update.form.constant
    assert [(r.module, r.param) for r in update.form.reads] == [("ctrl", "kp")]
    constant = _load(tmp_path, "adjust ctrl.kp = 100.0 * 2.0")
    task = next(t for t in constant.program.robottasks if t.name == "TrackPID")
    instance = instantiate(task, {r.name: r for r in constant.program.robots}, constant.host)
    assert instance.adjustments["Saturated"].value == 200.0
