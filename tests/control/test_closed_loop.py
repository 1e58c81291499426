"""Closed loop without the executive: PID vs computed torque on the MuJoCo arm (§7.1).

q_d = q0 (1 + cos(pi t)), q0 = [0.5, 0.5, 0.5] rad, 1 kHz for 4 s, same kp = 400 and
kv = 40: computed torque's RMS tracking error is at least 10x smaller than PID's and
both are stable. docs/control.md records the figures.
"""

import pytest

from orccad_app.commands.closed_loop import main
from orccad_app.control.closed_loop import simulate
from orccad_app.control.errors import ControlError
from orccad_app.control.spec import resolve

TASK = ("joint_tracking", {"trajectory": ("cosine", {"q0": [0.5, 0.5, 0.5]})})


def run(host, arm, law, **kwargs):
    task = resolve(host, "task function", TASK).build(arm)
    return simulate(resolve(host, "control law", law).build(arm, task), **kwargs)


@pytest.fixture(scope="module")
def results(host, arm):
    return {name: run(host, arm, (name, gains), duration_s=4.0, rate_hz=1000.0)
            for name, gains in (("pid", {"kp": 400.0, "kv": 40.0, "ki": 10.0}),
                                ("computed_torque", {"kp": 400.0, "kv": 40.0}))}


def test_both_laws_are_stable(results):
    for result in results.values():
        assert result.stable
        assert len(result.times) == 4000 and result.times[-1] == pytest.approx(3.999)


def test_computed_torque_is_at_least_ten_times_more_accurate_than_pid(results):
    pid, computed = results["pid"], results["computed_torque"]
    assert computed.rms_error * 10 <= pid.rms_error
    assert pid.rms_error < 0.05 and computed.rms_error < 1e-3


def test_no_saturation_on_the_nominal_task(results):
    for result in results.values():
        assert result.saturation_ratio == 0.0 and result.peak_torque < 60.0


def test_a_perturbed_model_degrades_computed_torque(host, arm, results):
    perturbed = run(host, arm, ("computed_torque", {"model": "perturbed", "perturbation": 0.3}),
                    duration_s=1.0)
    assert perturbed.stable
    assert perturbed.rms_error > 10 * results["computed_torque"].rms_error


def test_the_rate_must_divide_the_plant_rate(host, arm):
    with pytest.raises(ControlError, match="rate_hz = 300.0 must divide the plant rate 1000 Hz"):
        run(host, arm, ("pid", {}), duration_s=0.01, rate_hz=300.0)


def test_the_command_reports_both_laws(capsys):
    assert main(["--duration", "0.5"]) == 0
    out = capsys.readouterr().out
    assert "pid" in out and "computed_torque" in out and "RMS ratio" in out


def test_the_command_reports_unknown_laws_without_traceback(capsys):
    assert main(["--laws", "pidd", "--duration", "0.1"]) == 2
    err = capsys.readouterr().err
    assert "unknown control law 'pidd'" in err and "Traceback" not in err
