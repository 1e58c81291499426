"""The lean path of ``law.command`` (laws/fast.py) computes bit for bit what the general
path computes, saturation, anti-windup and signed zeros included — except computed torque,
whose one ``rnea`` call agrees with the general path's ``crba`` + products +
``nonLinearEffects`` to rounding."""

import math

import numpy as np
import pytest

from orccad_app.control.spec import resolve

LAWS = [("pid", {"kp": 400.0, "kv": 40.0, "ki": 10.0}),
        ("pid", {"kp": [300.0, 200.0, 100.0], "kv": 30.0, "ki": 0.0}),
        ("computed_torque", {"kp": 400.0, "kv": 40.0})]


def _law(host, arm, call):
    task = resolve(host, "task function", ("joint_tracking", {
        "trajectory": ("cosine", {"q0": [0.5, 0.5, 0.5], "omega": math.pi})})).build(arm)
    return resolve(host, "control law", call).build(arm, task), task


@pytest.mark.parametrize("call", LAWS, ids=lambda c: c[0])
def test_lean_and_general_paths_agree_bit_for_bit(host, arm, call):
    lean, task = _law(host, arm, call)
    general, _ = _law(host, arm, call)
    assert lean._lean is not None
    general._lean = None
    rng = np.random.default_rng(1)
    saturated = 0
    for k in range(400):
        t = k * 1e-3
        # large excursions saturate the torques (anti-windup), k = 0 gives exact zeros
        scale = 0.0 if k == 0 else (2.0 if k % 50 < 10 else 0.05)
        reference = task.reference(t)
        q = reference.pos + rng.normal(0.0, scale, 3)
        qdot = reference.vel + rng.normal(0.0, 10 * scale, 3)
        a, b = lean.command(t, q, qdot, reference), general.command(t, q, qdot, reference)
        if call[0] == "computed_torque":  # M a + N in one rnea: equal to rounding
            assert a.e.tobytes() == b.e.tobytes(), k
            np.testing.assert_allclose(a.tau_unsat, b.tau_unsat, rtol=1e-12, atol=1e-9)
            np.testing.assert_allclose(a.tau, b.tau, rtol=1e-12, atol=1e-9)
            saturated += bool(a.saturated.any())
            continue
        for name in ("tau", "tau_unsat", "saturated", "e"):
            x, y = getattr(a, name), getattr(b, name)
            assert x.tobytes() == y.tobytes(), (k, name, x, y)
        assert lean.integral.tobytes() == general.integral.tobytes()
        saturated += bool(a.saturated.any())
    assert 0 < saturated < 400


def test_wrong_shape_goes_through_the_general_path_and_raises_as_before(host, arm):
    law, task = _law(host, arm, LAWS[0])
    with pytest.raises(ValueError):
        law.command(0.0, np.zeros(2), np.zeros(2), task.reference(0.0))


def _special_states(rng, count):
    """Joint states that hit the plain-float path's corner cases: exact zeros of both signs,
    errors that land exactly on a torque bound (ties in max/min), huge values, NaN and inf."""
    specials = [0.0, -0.0, 1e-300, -1e-300, 1e300, math.nan, math.inf, -math.inf]
    for k in range(count):
        q, qdot = rng.normal(0.0, 1.0, 3), rng.normal(0.0, 5.0, 3)
        if k % 3 == 0:
            q[rng.integers(3)] = specials[rng.integers(len(specials) - 3)]
            qdot[rng.integers(3)] = specials[rng.integers(len(specials) - 3)]
        if k % 17 == 0:
            q[rng.integers(3)] = specials[rng.integers(len(specials))]
        yield q, qdot


@pytest.mark.filterwarnings("ignore::RuntimeWarning")  # NaN inputs, numpy side
@pytest.mark.parametrize("call", LAWS, ids=["pid", "pid-no-integral", "computed-torque"])
def test_plain_float_path_equals_the_numpy_lean_path(host, arm, call):
    """The plain-float path (small robots) against the numpy lean path, bit for bit, with the
    integral and the saturation directions it keeps."""
    floats, task = _law(host, arm, call)
    arrays, _ = _law(host, arm, call)
    assert floats._lean.scalar
    arrays._lean.scalar = False
    rng = np.random.default_rng(7)
    for k, (q, qdot) in enumerate(_special_states(rng, 3000)):
        t = (k // 2) * 1e-3  # repeated instants: dt = 0
        reference = task.reference(t)
        if k % 5 == 0:  # a torque exactly on its bound: e chosen so that kp e hits it
            q = reference.pos + floats._lean.high / -400.0
            qdot = reference.vel.copy()
        if k % 7 == 0:  # finite inputs, overflowing torques (inf - inf: NaN)
            q, qdot = reference.pos + 1e307, reference.vel - 1e308
        a = floats.command(t, q, qdot, reference)
        b = arrays.command(t, q, qdot, reference)
        for name in ("tau", "tau_unsat", "saturated", "e"):
            x, y = getattr(a, name), getattr(b, name)
            assert x.tobytes() == y.tobytes(), (k, name, x, y)
        assert floats.integral.tobytes() == arrays.integral.tobytes(), k
        assert floats._sat_dir.tobytes() == arrays._sat_dir.tobytes(), k
        if not np.all(np.isfinite(floats.integral)):  # start again after a NaN
            floats.reset()
            arrays.reset()
