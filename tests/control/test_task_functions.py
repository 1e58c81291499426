"""Task functions: joint tracking (eq. 6-7) and Cartesian tracking with DLS."""

import numpy as np
import pytest

from orccad_app.control.errors import ControlError, DimensionMismatch
from orccad_app.control.catalogue import CARTESIAN_TRACKING, JOINT_TRACKING
from orccad_app.control.task_functions import CartesianTracking, JointTracking
from orccad_app.control.trajectories import Constant, Cosine, MinimumJerk, Sample

REF = Sample(pos=np.array([1.0, 0.5, -0.2]), vel=np.array([0.1, 0.0, -0.3]),
             acc=np.array([2.0, -1.0, 0.5]))


def test_joint_tracking_terms_are_those_of_equations_6_and_7():
    task = JointTracking(3, Cosine([0.5, 0.5, 0.5]))
    q, qdot = np.array([1.1, 0.4, 0.0]), np.array([0.2, 0.1, 0.0])
    state = task.evaluate(q, qdot, REF)
    np.testing.assert_allclose(state.e, q - REF.pos)
    np.testing.assert_allclose(state.e_dot, qdot - REF.vel)
    np.testing.assert_array_equal(state.jacobian, np.eye(3))
    np.testing.assert_array_equal(state.jacobian_inv, np.eye(3))
    np.testing.assert_allclose(state.de_dt, -REF.vel)
    np.testing.assert_allclose(state.f, -REF.acc)


def test_dimension_of_the_trajectory_must_match_dim_e():
    with pytest.raises(DimensionMismatch, match="trajectory 'cosine' has 2 components but the "
                                                "task function has dim e = 3"):
        JointTracking(3, Cosine([0.5, 0.5]))


def test_joint_tracking_starts_a_trajectory_from_the_measurement():
    task = JointTracking(2, MinimumJerk(goal=[1.0, 1.0], duration=1.0))
    task.start_from(np.array([0.2, 0.4]))
    np.testing.assert_allclose(task.reference(0.0).pos, [0.2, 0.4])


@pytest.fixture
def cartesian(arm):
    return CartesianTracking(arm.pinocchio_model(), Constant([0.6, 0.0, 0.8]), "end_effector",
                             damping=0.01)


def test_cartesian_jacobian_matches_finite_differences(cartesian):
    q = np.array([0.3, 0.7, 1.1])
    jacobian = cartesian.jacobian(q)
    numeric = np.zeros((3, 3))
    for j in range(3):
        step = np.zeros(3)
        step[j] = 1e-6
        numeric[:, j] = (cartesian.measure(q + step) - cartesian.measure(q - step)) / 2e-6
    np.testing.assert_allclose(jacobian, numeric, atol=1e-7)


def test_cartesian_f_is_jdot_qdot_minus_the_desired_acceleration(cartesian):
    q, qdot = np.array([0.3, 0.7, 1.1]), np.array([0.5, -0.4, 0.9])
    h = 1e-6
    jdot = (cartesian.jacobian(q + h * qdot) - cartesian.jacobian(q - h * qdot)) / (2 * h)
    state = cartesian.evaluate(q, qdot, REF)
    np.testing.assert_allclose(state.f, jdot @ qdot - REF.acc, atol=1e-6)
    np.testing.assert_allclose(state.e, cartesian.measure(q) - REF.pos)
    np.testing.assert_allclose(state.e_dot, state.jacobian @ qdot - REF.vel)


def test_dls_inverse_is_a_regularized_inverse(cartesian):
    q = np.array([0.3, 0.7, 1.1])
    jacobian = cartesian.jacobian(q)
    inverse = cartesian.dls_inverse(jacobian)
    np.testing.assert_allclose(jacobian @ inverse, np.eye(3), atol=1e-2)
    cartesian.damping = 0.0
    np.testing.assert_allclose(cartesian.dls_inverse(jacobian), np.linalg.inv(jacobian),
                               atol=1e-9)


def test_dls_inverse_stays_bounded_at_a_singularity(cartesian):
    singular = cartesian.jacobian(np.array([0.0, 0.3, 0.0]))  # elbow stretched
    assert np.linalg.svd(singular, compute_uv=False)[-1] < 1e-9
    bound = 1.0 / (2 * cartesian.damping)  # max of s / (s² + λ²)
    assert np.linalg.norm(cartesian.dls_inverse(singular), 2) <= bound + 1e-9


def test_kinds_build_from_the_robot(arm):
    task = CARTESIAN_TRACKING.create({"trajectory": Constant([0.5, 0.0, 0.7])}, arm)
    assert task.frame == "end_effector" and task.dim == 3
    assert JOINT_TRACKING.create({"trajectory": Cosine([0.5] * 3)}, arm).dim == 3
    with pytest.raises(ControlError, match="no frame 'tool'"):
        CARTESIAN_TRACKING.create({"trajectory": Constant([0.5, 0.0, 0.7]),
                                   "frame": "tool"}, arm)
