"""A type-1 update of a trajectory parameter keeps the set-point continuous (issue 28, 4).

For every trajectory kind of the catalogue and every parameter a retune can change, the
trajectory module is driven as the executive drives it (1 ms jobs), retuned mid-motion, and the
set-point must not jump: consecutive samples around the update differ by what the velocity
allows in one period, velocity and acceleration too; after the blend the set-point is the new
trajectory's.
"""

from __future__ import annotations

import numpy as np
import pytest

from orccad_app.control.catalogue import TRAJECTORY_KINDS
from orccad_app.control.module_kinds import TrajectoryModule
from orccad_app.control.spec import module_context
from orccad_app.control.trajectories import BLEND_S

PERIOD_S = 0.001
START = [0.1, -0.2, 0.3]

# kind -> (parameters, {parameter: new value}); every retunable parameter of every kind
CASES = {
    "cosine": ({"q0": [0.62, 0.5, 0.4], "omega": 3.14159}, {"omega": 0.5, "q0": [0.3, 0.3, 0.3]}),
    "min_jerk": ({"goal": [1.0, 0.5, -0.5], "duration": 2.0, "start": START},
                 {"goal": [-0.5, 0.0, 0.8], "duration": 0.4, "start": [0.9, 0.9, 0.9]}),
    "constant": ({"value": [0.2, 0.1, 0.0]}, {"value": [1.0, -1.0, 0.5]}),
}


def test_every_kind_and_parameter_is_covered() -> None:
    for kind in TRAJECTORY_KINDS:
        assert kind.name in CASES, kind.name
        names = {p.name for p in kind.params if p.type != "trajectory"}
        assert set(CASES[kind.name][1]) == names, kind.name


def _module(host, kind: str, params: dict):
    context = module_context(host, "arm3dof", ("joint_tracking", {"trajectory": (kind, params)}))
    module = TrajectoryModule().create({}, context)
    module.init()
    return module


CHANGES = [(kind, name, value) for kind, (_, changes) in CASES.items()
           for name, value in changes.items()]


@pytest.mark.parametrize("kind, name, value", CHANGES, ids=[f"{k}.{n}" for k, n, _ in CHANGES])
def test_a_retune_keeps_the_set_point_continuous(host, kind, name, value) -> None:
    params = CASES[kind][0]
    module = _module(host, kind, params)
    at_s = 1.237  # mid-motion: the cosine far from a turning point, min_jerk moving
    samples = []
    t = 0.0
    while t < at_s + 2 * BLEND_S:
        if abs(t - at_s) < PERIOD_S / 2:
            module.set_param(name, value)
        out = module.compute(t, {"q": START})
        samples.append((t, out["qd"], out["qd_dot"], out["qd_ddot"]))
        t = round(t + PERIOD_S, 9)
    bound_pos = max(np.max(np.abs(v)) for _, _, v, _ in samples) * PERIOD_S * 1.5 + 1e-9
    bound_vel = max(np.max(np.abs(a)) for _, _, _, a in samples) * PERIOD_S * 1.5 + 1e-9
    for (_, q0, v0, _), (t1, q1, v1, _) in zip(samples, samples[1:]):
        assert np.max(np.abs(q1 - q0)) <= bound_pos, f"set-point jumps at {t1:.3f} s"
        assert np.max(np.abs(v1 - v0)) <= bound_vel, f"velocity jumps at {t1:.3f} s"
    reference = _module(host, kind, {**params, name: value})
    last_t, last_q = samples[-1][0], samples[-1][1]
    reference.compute(0.0, {"q": START})  # its task time from 0, as the module's
    expected = reference.compute(last_t, {"q": START})["qd"]
    if kind != "cosine":  # cosine: the new frequency from the old phase (a shifted time)
        np.testing.assert_allclose(last_q, expected, atol=1e-12)


def test_retuning_omega_keeps_the_phase(host) -> None:
    """The docs' example: retuning the cosine's omega mid-motion leaves the set-point where it
    was (the frequency changes from the current phase on)."""
    module = _module(host, "cosine", CASES["cosine"][0])
    module.compute(0.0, {})
    before = module.compute(1.237, {})
    module.set_param("omega", 0.5)
    after = module.compute(1.238, {})
    np.testing.assert_allclose(after["qd"], before["qd"], atol=0.01)
    later = module.compute(1.237 + 2 * BLEND_S, {})
    phase = 3.14159 * 1.237 + 0.5 * 2 * BLEND_S  # old phase, then the new frequency
    np.testing.assert_allclose(later["qd"], np.array([0.62, 0.5, 0.4]) * (1 + np.cos(phase)),
                               atol=1e-9)
