"""Trajectories: eq. 9-10, minimum jerk, constant; derivatives are consistent."""

import math

import numpy as np
import pytest

from orccad_app.control.errors import DimensionMismatch, InvalidParameter
from orccad_app.control.catalogue import COSINE, MINIMUM_JERK
from orccad_app.control.trajectories import Constant, Cosine, MinimumJerk

Q0 = np.array([0.5, 0.5, 0.5])


def numeric_derivatives(trajectory, t, h=1e-6):
    before, after = trajectory.sample(t - h), trajectory.sample(t + h)
    return (after.pos - before.pos) / (2 * h), (after.vel - before.vel) / (2 * h)


def test_cosine_matches_equations_9_and_10():
    trajectory = Cosine(Q0)
    for t in (0.0, 0.25, 1.0, 1.7, 3.9):
        sample = trajectory.sample(t)
        np.testing.assert_allclose(sample.pos, Q0 * (1 + math.cos(math.pi * t)))
        np.testing.assert_allclose(sample.vel, -Q0 * math.pi * math.sin(math.pi * t))
    assert trajectory.sample(0.0).pos.tolist() == [1.0, 1.0, 1.0]
    assert trajectory.end_time_s is None and trajectory.final() is None


@pytest.mark.parametrize("trajectory", [
    Cosine(Q0, omega=2.0),
    MinimumJerk(goal=[1.0, -0.5], duration=2.0, start=[0.0, 0.5]),
])
@pytest.mark.parametrize("t", [0.3, 0.9, 1.5])
def test_velocity_and_acceleration_are_the_derivatives(trajectory, t):
    velocity, acceleration = numeric_derivatives(trajectory, t)
    sample = trajectory.sample(t)
    np.testing.assert_allclose(sample.vel, velocity, atol=1e-6)
    np.testing.assert_allclose(sample.acc, acceleration, atol=1e-5)


def test_minimum_jerk_starts_and_ends_at_rest_then_holds_the_goal():
    trajectory = MinimumJerk(goal=[1.0, 2.0], duration=2.0, start=[0.0, 0.0])
    for t, position in ((0.0, [0.0, 0.0]), (1.0, [0.5, 1.0]), (2.0, [1.0, 2.0]),
                        (5.0, [1.0, 2.0])):
        sample = trajectory.sample(t)
        np.testing.assert_allclose(sample.pos, position)
    for t in (0.0, 2.0, 3.0):
        np.testing.assert_allclose(trajectory.sample(t).vel, 0.0, atol=1e-12)
        np.testing.assert_allclose(trajectory.sample(t).acc, 0.0, atol=1e-12)
    assert trajectory.final().tolist() == [1.0, 2.0]
    # peak velocity of a minimum-jerk move: 15/8 * distance / duration
    np.testing.assert_allclose(trajectory.sample(1.0).vel, [15 / 16, 15 / 8])


def test_minimum_jerk_without_start_takes_the_measurement():
    trajectory = MinimumJerk(goal=[1.0], duration=1.0)
    assert trajectory.needs_start
    with pytest.raises(InvalidParameter, match="no start position"):
        trajectory.sample(0.0)
    started = trajectory.with_start(np.array([0.2]))
    assert not started.needs_start
    np.testing.assert_allclose(started.sample(0.0).pos, [0.2])


def test_minimum_jerk_checks_its_arguments():
    with pytest.raises(InvalidParameter, match=r"duration must be in \[1 us, one year\].*got 0"):
        MinimumJerk(goal=[1.0], duration=0)
    with pytest.raises(DimensionMismatch, match="start has 2 components but goal has 1"):
        MinimumJerk(goal=[1.0], duration=1.0, start=[0.0, 0.0])


def test_constant_holds_its_value_or_the_first_measurement():
    sample = Constant([0.1, 0.2]).sample(7.0)
    assert sample.pos.tolist() == [0.1, 0.2] and not sample.vel.any() and not sample.acc.any()
    held = Constant().with_start(np.array([0.3]))
    assert held.sample(1.0).pos.tolist() == [0.3]


def test_kinds_validate_parameters():
    assert COSINE.create({"q0": [0.5, 0.5, 0.5]}).omega == pytest.approx(math.pi)
    with pytest.raises(InvalidParameter, match="omega must be > 0"):
        COSINE.create({"q0": [0.5], "omega": -1.0})
    with pytest.raises(InvalidParameter, match="missing parameter 'goal'"):
        MINIMUM_JERK.create({"duration": 1.0})


@pytest.mark.parametrize("make", [
    lambda: MinimumJerk([1e308, 0.0, 0.0], 1.0, [0.0, 0.0, 0.0]),
    lambda: MinimumJerk([1.0, 0.0, 0.0], 1e-300, [0.0, 0.0, 0.0]),
    lambda: Cosine([1e308, 0.5, 0.5]),
    lambda: Cosine([0.5, 0.5, 0.5], 1e300),
    lambda: Constant([float("nan"), 0.0, 0.0]),
])
def test_trajectories_whose_set_point_would_not_stay_finite_are_refused(make):
    # a goal of 1e308 ended the run done with an infinite tracking error (issue 28)
    with pytest.raises(InvalidParameter, match="must be"):
        make()
