"""Backward differences for unconnected velocity inputs."""

import numpy as np

from orccad_app.control.estimation import BackwardDifference


def test_each_sample_counts_for_a_sensor():
    estimator = BackwardDifference()
    assert estimator.update(0.0, [1.0]).tolist() == [0.0]
    assert estimator.update(0.5, [2.0]).tolist() == [2.0]
    assert estimator.update(1.0, [2.0]).tolist() == [0.0]


def test_repeated_values_are_stale_for_a_slower_producer():
    estimator = BackwardDifference(on_change=True)
    estimator.update(0.0, [0.0])
    np.testing.assert_allclose(estimator.update(0.002, [0.004]), [2.0])
    np.testing.assert_allclose(estimator.update(0.003, [0.004]), [2.0])  # held
    np.testing.assert_allclose(estimator.update(0.004, [0.008]), [2.0])
    estimator.reset()
    assert estimator.update(1.0, [5.0]).tolist() == [0.0]
