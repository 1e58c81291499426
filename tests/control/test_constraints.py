"""The actuator constraint max(Γmin, -α - βq̇) <= Γ <= min(Γmax, α - βq̇)."""

import numpy as np
import pytest

from orccad_app.control.constraints import ActuatorConstraint
from orccad_app.control.errors import DimensionMismatch, InvalidParameter

CONSTRAINT = ActuatorConstraint([-10.0, -20.0], [10.0, 20.0], alpha=[15.0, 30.0], beta=[2.0, 1.0])


def test_bounds_follow_the_formula_of_section_3_1_2():
    qdot = np.array([3.0, -4.0])
    low, high = CONSTRAINT.bounds(qdot)
    alpha, beta = np.array([15.0, 30.0]), np.array([2.0, 1.0])
    np.testing.assert_allclose(low, np.maximum([-10.0, -20.0], -alpha - beta * qdot))
    np.testing.assert_allclose(high, np.minimum([10.0, 20.0], alpha - beta * qdot))
    assert low.tolist() == [-10.0, -20.0] and high.tolist() == [9.0, 20.0]


def test_at_rest_only_the_torque_limits_apply():
    low, high = CONSTRAINT.bounds([0.0, 0.0])
    assert low.tolist() == [-10.0, -20.0] and high.tolist() == [10.0, 20.0]


def test_apply_clips_and_reports_saturated_joints():
    tau, saturated = CONSTRAINT.apply([12.0, -5.0], [0.0, 0.0])
    assert tau.tolist() == [10.0, -5.0] and saturated.tolist() == [True, False]
    assert CONSTRAINT.at_bound(tau, [0.0, 0.0]).tolist() == [True, False]


def test_at_very_high_speed_the_current_limit_wins():
    low, high = CONSTRAINT.bounds([20.0, 0.0])  # alpha - beta qdot = -25 < tau_min = -10
    assert low[0] == high[0] == -10.0


def test_scalars_broadcast_and_alpha_defaults_to_plain_saturation():
    constraint = ActuatorConstraint(-1.0, [1.0, 2.0])
    low, high = constraint.bounds([100.0, -100.0])
    assert low.tolist() == [-1.0, -1.0] and high.tolist() == [1.0, 2.0]


@pytest.mark.parametrize("args, error, fragment", [
    (([1.0], [1.0]), InvalidParameter, "tau_min [1.0] must be < tau_max [1.0]"),
    (([-1.0], [1.0], 0.0), InvalidParameter, "alpha must be > 0, got [0.0]"),
    (([-1.0], [1.0], 1.0, -1.0), InvalidParameter, "beta must be finite and >= 0"),
    (([-1.0, -1.0, -1.0], [1.0, 1.0]), DimensionMismatch, "tau_min has 3 values, expected 2"),
])
def test_invalid_constraints_name_the_bad_value(args, error, fragment):
    with pytest.raises(error) as caught:
        ActuatorConstraint(*args)
    assert fragment in str(caught.value)


def test_wrong_velocity_shape_is_rejected():
    with pytest.raises(DimensionMismatch, match=r"qdot has shape \(3,\), expected \(2,\)"):
        CONSTRAINT.bounds([0.0, 0.0, 0.0])
