"""The observer library on synthetic signals, driven like the executive does."""

import math

import pytest

from orccad_app.control.errors import ControlError
from orccad_app.control.module import ModuleContext
from orccad_app.control.spec import module_context
from orccad_app.diagnostics import OrccadError

from orccad_observers import OBSERVERS

COSINE_TASK = ("joint_tracking", {"trajectory": ("cosine", {"q0": [0.5, 0.5, 0.5]})})


@pytest.fixture
def context(host):
    return module_context(host, "arm3dof", COSINE_TASK, ("pid", {}), duration_s=4.0)


def make(host, context, kind, **params):
    instance = host.module_kind(kind).create(params, context)
    instance.init()
    return instance


def feed(instance, samples, period=0.005):
    """Run one job per input dict; the list of job indices where the event fired."""
    fired = []
    for k, inputs in enumerate(samples):
        if instance.compute(k * period, inputs).get("event"):
            fired.append(k)
    return fired


def test_every_observer_has_typed_inputs_and_an_event_output(host, context):
    assert len(OBSERVERS) == 7
    for kind in OBSERVERS:
        assert kind.is_observer and kind.event_ports == ("event",)
        assert any(p.direction == "in" for p in kind.ports)
        assert kind.default_timing.period_ns == 5_000_000
        assert host.observers.get(kind.name) is kind


def test_joint_limits_fires_within_the_margin(host, context):
    observer = make(host, context, "joint_limits", margin=0.1)
    assert observer.port("q").dim == 3
    samples = [{"q": [0.0, q2, 0.0]} for q2 in (1.0, 1.45, 1.51, 1.55, 1.2)]  # upper 1.6
    assert feed(observer, samples) == [2, 3]
    out = observer.compute(1.0, {"q": [0.0, 1.55, 0.0]})
    assert out["value"] == pytest.approx(0.05)
    assert feed(observer, [{"q": [-2.85, 0.0, 0.0]}]) == [0]  # lower limit of j1 is -2.9


def test_joint_limits_margin_must_leave_room(host, context):
    with pytest.raises(ControlError, match="margin 2.0 rad leaves no room in the range of "
                                           "joint 'j2'"):
        host.module_kind("joint_limits").create({"margin": 2.0}, context)
    with pytest.raises(ControlError, match="joint_limits needs a robot"):
        host.module_kind("joint_limits").create({}, ModuleContext())


def test_edge_mode_fires_once_per_crossing(host, context):
    observer = make(host, context, "joint_limits", margin=0.1, edge=True)
    samples = [{"q": [0.0, q2, 0.0]} for q2 in (1.0, 1.55, 1.56, 1.0, 1.58)]
    assert feed(observer, samples) == [1, 4]


def test_tracking_error_reads_e_or_q_minus_qd(host, context):
    observer = make(host, context, "tracking_error", max=0.2)
    assert observer.port("e").dim == 3
    assert feed(observer, [{"e": [0.1, -0.1, 0.0]}, {"e": [0.0, -0.25, 0.0]},
                           {"q": [1.0] * 3, "qd": [1.0, 1.3, 1.0]}, {"q": [1.0] * 3}]) == [1, 2]
    assert observer.compute(0.0, {"q": [1.0] * 3}) == {}


def test_singularity_fires_when_the_elbow_stretches(host, context):
    observer = make(host, context, "singularity", threshold=0.01)
    elbow = [1.0, 0.5, 0.2, 0.05, 0.0, 1.0]
    fired = feed(observer, [{"q": [0.0, 0.3, q3]} for q3 in elbow])
    assert fired == [3, 4]
    bent = observer.compute(0.0, {"q": [0.0, 0.3, 1.0]})["value"]
    straight = observer.compute(0.0, {"q": [0.0, 0.3, 0.0]})["value"]
    assert bent > 0.05 and straight < 1e-9


def test_torque_saturation_follows_the_actuator_constraint(host, context):
    observer = make(host, context, "torque_saturation")
    samples = [{"tau": [10.0, 0.0, 0.0]}, {"tau": [80.0, 0.0, 0.0]},
               {"tau": [0.0, -120.0, 0.0]},
               {"tau": [0.0, 80.0, 0.0], "qdot": [0.0, 4.0, 0.0]},  # 200 - 30 * 4 = 80 N·m
               {"tau": [0.0, 80.0, 0.0], "qdot": [0.0, 0.0, 0.0]}]
    assert feed(observer, samples) == [1, 2, 3]
    assert observer.compute(0.0, {"tau": [40.0, 0.0, 0.0]})["value"] == pytest.approx(0.5)
    early = make(host, context, "torque_saturation", ratio=0.5)
    assert feed(early, [{"tau": [40.0, 0.0, 0.0]}]) == [0]


def test_at_rest_fires_while_every_speed_is_small(host, context):
    observer = make(host, context, "at_rest", tol=0.01)
    speeds = [[0.5, 0.0, 0.0], [0.009, -0.009, 0.0], [0.0, 0.02, 0.0], [0.0, 0.0, 0.0]]
    assert feed(observer, [{"qdot": s} for s in speeds]) == [1, 3]


def test_at_goal_waits_for_the_end_of_the_reference(host, context):
    observer = make(host, context, "at_goal", tol=0.005)
    goal = [1.0, 1.0, 1.0]  # cosine: q_d(T = 4 s) = 2 q0
    assert observer.compute(0.0, {"q": goal}) == {"value": 0.0}  # at t = 0: not yet
    assert observer.compute(3.99, {"q": goal}).get("event") is None
    assert observer.compute(4.0, {"q": goal})["event"] is True
    assert observer.compute(4.1, {"q": [1.0, 1.01, 1.0]}).get("event") is None


def test_at_goal_with_a_point_to_point_trajectory_or_an_explicit_goal(host):
    context = module_context(host, "arm3dof", ("joint_tracking", {
        "trajectory": ("min_jerk", {"goal": [0.2, 0.0, 0.0], "duration": 1.0})}))
    observer = make(host, context, "at_goal", tol=0.01, vel_tol=0.05)
    assert feed(observer, [{"q": [0.2, 0.0, 0.0]}]) == []  # t = 0 < duration
    assert observer.compute(1.0, {"q": [0.205, 0.0, 0.0], "qdot": [0.0] * 3})["event"]
    assert "event" not in observer.compute(1.1, {"q": [0.205, 0.0, 0.0], "qdot": [0.1, 0, 0]})
    explicit = make(host, ModuleContext(robot=context.robot), "at_goal", tol=0.01,
                    goal=[0.0, 0.0, 0.0])
    assert feed(explicit, [{"q": [0.0, 0.005, 0.0]}, {"q": [0.0, 0.05, 0.0]}]) == [0]
    assert explicit.compute(0.0, {"q": [0.5] * 3, "goal": [0.5] * 3})["event"]


def test_at_goal_needs_a_goal(host):
    with pytest.raises(ControlError, match="never ends and the Robot-Task has no duration"):
        host.module_kind("at_goal").create({"tol": 0.01}, module_context(
            host, "arm3dof", COSINE_TASK))
    with pytest.raises(ControlError, match="no goal"):
        host.module_kind("at_goal").create({"tol": 0.01}, ModuleContext())


def test_sensor_threshold_watches_a_robot_sensor(host, context):
    kind = host.module_kind("sensor_threshold")
    params = {"sensor": "qdot", "direction": "above", "value": 2.0, "absolute": True}
    assert kind.sources(params) == {"signal": "qdot"}
    observer = make(host, context, "sensor_threshold", **params)
    assert observer.port("signal").dim == 3
    assert feed(observer, [{"signal": [0.0, 1.0, 0.0]}, {"signal": [0.0, -2.5, 0.0]}]) == [1]
    below = make(host, context, "sensor_threshold", sensor="q", direction="below",
                 value=0.0, index=2)
    assert feed(below, [{"signal": [-1.0, -1.0, 0.5]}, {"signal": [1.0, 1.0, -0.1]}]) == [1]


@pytest.mark.parametrize("params, fragment", [
    ({"sensor": "tau", "direction": "above", "value": 1.0}, "'tau' is an actuator"),
    ({"sensor": "qdt", "direction": "above", "value": 1.0}, "did you mean 'qdot'"),
    ({"sensor": "q", "direction": "over", "value": 1.0}, "direction must be one of"),
    ({"sensor": "q", "direction": "above", "value": 1.0, "index": 3}, "index 3 is out of range"),
])
def test_sensor_threshold_checks_its_parameters(host, context, params, fragment):
    with pytest.raises(OrccadError, match=fragment):
        host.module_kind("sensor_threshold").create(params, context)


def test_parameters_are_adjustable_between_jobs(host, context):
    observer = make(host, context, "tracking_error", max=0.2)
    assert feed(observer, [{"e": [0.15, 0.0, 0.0]}]) == []
    observer.set_param("max", 0.1)
    assert observer.compute(1.0, {"e": [0.15, 0.0, 0.0]})["event"] is True


def test_a_closed_loop_trace_triggers_the_expected_observers(host, context):
    """PID on the cosine task: no joint limit, no lost tracking, at goal at T."""
    from orccad_app.control.closed_loop import simulate

    law = context.law.build(context.robot, context.task_function.build(context.robot))
    result = simulate(law, duration_s=4.0, rate_hz=200.0)
    limits = make(host, context, "joint_limits", margin=0.1)
    lost = make(host, context, "tracking_error", max=0.2)
    for t, q, e in zip(result.times, result.q, result.errors):
        assert "event" not in limits.compute(t, {"q": q})
        assert "event" not in lost.compute(t, {"e": e})
    assert math.isclose(result.times[-1], 3.995)


@pytest.mark.filterwarnings("ignore::RuntimeWarning")  # NaN inputs, numpy side
@pytest.mark.parametrize("kind", ["joint_limits", "torque_saturation"])
def test_limit_monitors_on_floats_equal_the_numpy_path(host, context, monkeypatch, kind):
    """The plain-float path of the limit observers (a few joints) gives the numpy path's
    values bit for bit: exact ties, signed zeros, bounds reached, non-finite inputs."""
    import numpy as np

    from orccad_observers import limits

    floats = make(host, context, kind)
    rng = np.random.default_rng(3)
    special = [0.0, -0.0, 1.6, -1.6, 150.0, -150.0, 1e300, math.nan, math.inf]
    samples = []
    for k in range(2000):
        a, b = rng.normal(0.0, 1.0, 3) * (1.0 if k % 2 else 100.0), rng.normal(0.0, 4.0, 3)
        if k % 3 == 0:
            a[rng.integers(3)] = special[rng.integers(len(special) - 2)]
            b[rng.integers(3)] = special[rng.integers(len(special) - 2)]
        if k % 29 == 0:
            a[rng.integers(3)] = special[rng.integers(len(special))]
        samples.append({"q": a} if kind == "joint_limits" else {"tau": a, "qdot": b})
    got = [floats.monitor(0.0, inputs) for inputs in samples]
    monkeypatch.setattr(limits, "SCALAR_DIM", 0)
    want = [floats.monitor(0.0, inputs) for inputs in samples]
    for k, ((hold_a, value_a), (hold_b, value_b)) in enumerate(zip(got, want)):
        assert hold_a == hold_b, k
        assert np.float64(value_a).tobytes() == np.float64(value_b).tobytes(), (k, value_a,
                                                                               value_b)
