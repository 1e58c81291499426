"""Control laws: eq. 5, PID (eq. 8) with anti-windup, computed torque, coherence checks."""

import numpy as np
import pytest

from orccad_app.control.errors import DimensionMismatch, InvalidParameter
from orccad_app.control.catalogue import (
    COMPUTED_TORQUE_KIND,
    GENERIC_KIND,
    PID_KIND,
)
from orccad_app.control.models import PinocchioModel
from orccad_app.control.task_functions import JointTracking
from orccad_app.control.trajectories import Cosine, Sample
from orccad_app.diagnostics import OrccadError

Q = np.array([0.9, 1.1, 0.7])
QDOT = np.array([0.2, -0.3, 0.1])
REF = Sample(pos=np.array([1.0, 1.0, 1.0]), vel=np.array([0.1, 0.0, -0.2]),
             acc=np.array([0.5, -0.5, 1.0]))


@pytest.fixture
def task(arm):
    return JointTracking(arm.dof, Cosine([0.5, 0.5, 0.5]))


def test_pid_is_equation_8_with_negative_feedback(arm, task):
    law = PID_KIND.create({"kp": 400.0, "kv": 40.0, "ki": 10.0, "anti_windup": False},
                          arm, task)
    e, e_dot = Q - REF.pos, QDOT - REF.vel
    first = law.command(0.0, Q, QDOT, REF)
    np.testing.assert_allclose(first.tau_unsat, -(400.0 * e + 40.0 * e_dot))
    second = law.command(0.01, Q, QDOT, REF)  # integral of e over 10 ms
    np.testing.assert_allclose(second.tau_unsat,
                               -(400.0 * e + 40.0 * e_dot + 10.0 * e * 0.01))
    np.testing.assert_allclose(second.e, e)


def test_pid_accepts_per_joint_gains(arm, task):
    law = PID_KIND.create({"kp": [100.0, 200.0, 300.0], "kv": 1.0}, arm, task)
    out = law.command(0.0, Q, REF.vel, REF)
    np.testing.assert_allclose(out.tau_unsat, -np.array([100.0, 200.0, 300.0]) * (Q - REF.pos))


def test_computed_torque_decouples_with_the_pinocchio_model(arm, task):
    law = COMPUTED_TORQUE_KIND.create({"kp": 400.0, "kv": 40.0}, arm, task)
    model = PinocchioModel(arm.pinocchio_model())
    e, e_dot = Q - REF.pos, QDOT - REF.vel
    expected = model.mass_matrix(Q) @ (REF.acc - 400.0 * e - 40.0 * e_dot) + \
        model.nonlinear_effects(Q, QDOT)
    np.testing.assert_allclose(law.command(0.0, Q, QDOT, REF).tau_unsat, expected, atol=1e-9)


def test_generic_scheme_with_k_and_mu_equals_computed_torque(arm, task):
    generic = GENERIC_KIND.create({"k": 40.0, "mu": 10.0}, arm, task)
    computed = COMPUTED_TORQUE_KIND.create({"kp": 400.0, "kv": 40.0}, arm, task)
    np.testing.assert_allclose(generic.command(0.0, Q, QDOT, REF).tau_unsat,
                               computed.command(0.0, Q, QDOT, REF).tau_unsat, atol=1e-9)


def test_generic_scheme_with_identity_model_is_a_pd(arm, task):
    law = GENERIC_KIND.create({"k": 40.0, "mu": 10.0, "model": "identity"}, arm, task)
    e, e_dot = Q - REF.pos, QDOT - REF.vel
    np.testing.assert_allclose(law.command(0.0, Q, QDOT, REF).tau_unsat,
                               -40.0 * (10.0 * e + e_dot))


def test_generic_scheme_uses_g_and_d(arm, task):
    g, d = np.diag([1.0, 2.0, 3.0]), np.diag([0.5, 1.0, 2.0])
    law = GENERIC_KIND.create({"k": 2.0, "mu": 3.0, "G": g, "D": [0.5, 1.0, 2.0],
                               "model": "identity"}, arm, task)
    e, e_dot = Q - REF.pos, QDOT - REF.vel
    np.testing.assert_allclose(law.command(0.0, Q, QDOT, REF).tau_unsat,
                               -2.0 * g @ (3.0 * d @ e + e_dot))


def test_the_actuator_constraint_clips_the_output(arm, task):
    law = PID_KIND.create({"kp": 1e4, "kv": 1.0}, arm, task)
    out = law.command(0.0, Q, np.zeros(3), REF)
    assert out.saturated.any()
    low, high = arm.torque_limits
    assert np.all(out.tau <= high) and np.all(out.tau >= low)
    np.testing.assert_allclose(out.tau, np.clip(out.tau_unsat, low, high))


def test_anti_windup_stops_the_integral_while_saturated(arm, task):
    def integral_after(anti_windup):
        law = PID_KIND.create({"kp": 1e4, "kv": 1.0, "ki": 1e3,
                               "anti_windup": anti_windup}, arm, task)
        for k in range(200):
            law.command(k * 0.001, Q, np.zeros(3), REF)
        return law.integral

    e = Q - REF.pos
    np.testing.assert_allclose(integral_after(False), e * 0.199)  # 199 steps of 1 ms
    np.testing.assert_array_equal(integral_after(True), np.zeros(3))


def test_anti_windup_keeps_integrating_unsaturated_joints(arm, task):
    law = PID_KIND.create({"kp": [1e4, 1.0, 1.0], "kv": 1.0, "ki": 1.0}, arm, task)
    for k in range(11):
        law.command(k * 0.001, Q, np.zeros(3), REF)
    e = Q - REF.pos
    assert law.integral[0] == 0.0  # joint 1 saturated from the first job
    np.testing.assert_allclose(law.integral[1:], e[1:] * 0.01)


def test_set_param_retunes_and_keeps_the_integral(arm, task):
    law = PID_KIND.create({"kp": 400.0, "kv": 40.0, "ki": 10.0}, arm, task)
    law.command(0.0, Q, QDOT, REF)
    law.command(0.01, Q, QDOT, REF)
    integral = law.integral.copy()
    law.set_param("kp", 200.0)
    assert law.params["kp"] == 200.0 and np.array_equal(law.integral, integral)
    with pytest.raises(InvalidParameter, match="kp must be > 0, got -5.0"):
        law.set_param("kp", -5.0)
    assert law.params["kp"] == 200.0
    law.reset()
    assert not law.integral.any()


@pytest.mark.parametrize("kind, params, error, fragment", [
    (PID_KIND, {"kp": 0.0}, InvalidParameter, "pid: kp must be > 0, got 0.0"),
    (PID_KIND, {"kv": [1.0, -2.0, 1.0]}, InvalidParameter, "kv must be > 0, got [1.0, -2.0, 1.0]"),
    (PID_KIND, {"kp": [1.0, 2.0]}, DimensionMismatch, "pid: kp has 2 components, expected dim e = 3"),
    (GENERIC_KIND, {"k": 1.0, "mu": 1.0, "G": np.eye(2)}, DimensionMismatch,
     "generic: G must be 3×3, got shape (2, 2)"),
    (GENERIC_KIND, {"k": 1.0, "mu": 1.0, "D": -np.eye(3)}, InvalidParameter,
     "generic: D must be positive definite"),
    (GENERIC_KIND, {"k": 1.0, "mu": -1.0}, InvalidParameter, "generic: mu must be > 0, got -1.0"),
    (GENERIC_KIND, {"k": 1.0, "mu": 1.0, "model": "exact"}, InvalidParameter,
     "model must be one of 'identity', 'pinocchio', 'perturbed', got 'exact'"),
    (COMPUTED_TORQUE_KIND, {"perturbation": 1.5, "model": "perturbed"}, InvalidParameter,
     "perturbation must be in [0, 1), got 1.5"),
])
def test_coherence_checks_name_the_bad_value(arm, task, kind, params, error, fragment):
    with pytest.raises(error) as caught:
        kind.create(params, arm, task)
    assert fragment in str(caught.value)
    assert isinstance(caught.value, OrccadError)


def test_dim_e_must_equal_dim_q(arm):
    task = JointTracking(2, Cosine([0.5, 0.5]))
    with pytest.raises(DimensionMismatch, match=r"pid: dim e = 2 \(task function "
                                                r"'joint_tracking'\) must equal dim q = 3"):
        PID_KIND.create({}, arm, task)
