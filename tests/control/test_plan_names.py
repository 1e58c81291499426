"""Every name docs/language.md uses exists, and the TrackPID example composes.

The Robot-Task ``TrackPID`` (arm3dof, joint_tracking of cosine(q0, omega = pi), pid(kp, kv,
ki), modules traj/ctrl/jl and the observers named after ``from``) is assembled from the
registries by name and run job by job against the MuJoCo arm with last-value (asyn/asyn)
ports and zero execution times — the composition the executive will time.
"""

import math

import numpy as np
import pytest

from orccad_app.control.physics import RobotPhysics
from orccad_app.control.spec import module_context

TASK = ("joint_tracking", {"trajectory": ("cosine", {"q0": [0.5, 0.5, 0.5], "omega": math.pi})})
LAW = ("pid", {"kp": 400.0, "kv": 40.0, "ki": 10.0})
MODULES = {  # name: (kind, params, period [ms])
    "ctrl": ("control_law", {}, 1),
    "traj": ("trajectory", {}, 2),
    "jl": ("joint_limits", {"margin": 0.1}, 5),
}
CONNECTIONS = [("traj.qd", "ctrl.qd"), ("arm.q", "ctrl.q"), ("ctrl.tau", "arm.tau"),
               ("arm.q", "jl.q")]
OBSERVED = {  # observers named in 'from', with the kind's default timing
    "TrackingLost": ("tracking_error", {"max": 0.2}),
    "Saturated": ("torque_saturation", {}),
    "ArmReadyMeasured": ("at_rest", {"tol": 0.01}),
    "Tracked": ("at_goal", {"tol": 0.005}),
}


def test_every_name_of_section_3_is_registered(host):
    assert "arm3dof" in host.robot_types
    assert {"joint_tracking"} <= set(host.task_functions.names())
    assert {p.name for p in host.trajectories.get("cosine").params} == {"q0", "omega"}
    assert {"kp", "kv", "ki"} <= {p.name for p in host.control_laws.get("pid").params}
    for kind in ("trajectory", "control_law", "joint_limits", "tracking_error",
                 "torque_saturation", "at_rest", "at_goal"):
        host.module_kind(kind)
    arm = host.robot_types.get("arm3dof")
    assert {p.name for p in arm.ports} == {"q", "qdot", "tau"}


def build(host, law=LAW):
    context = module_context(host, "arm3dof", TASK, law, duration_s=4.0, robot_name="arm")
    modules = {name: host.module_kind(kind).create(params, context)
               for name, (kind, params, _) in MODULES.items()}
    for event, (kind, params) in OBSERVED.items():
        modules[event] = host.module_kind(kind).create(params, context)
    return context, modules


@pytest.fixture
def track_pid(host):
    return build(host)


def test_the_connections_join_ports_of_matching_type_and_dimension(track_pid):
    context, modules = track_pid
    robot = context.robot
    for source, target in CONNECTIONS:
        (producer, out), (consumer, port) = source.split("."), target.split(".")
        out_spec = (robot.port(out).spec if producer == "arm" else modules[producer].port(out))
        in_spec = (robot.port(port).spec if consumer == "arm" else modules[consumer].port(port))
        assert (out_spec.direction, in_spec.direction) == ("out", "in")
        assert (out_spec.type, out_spec.dim) == (in_spec.type, in_spec.dim), (source, target)


def run(context, modules, seconds, adjust_at=None):
    """1 ms ticks: plant step, then due modules by priority; last-value ports."""
    physics = RobotPhysics(context.robot)
    physics.set_state([1.0, 1.0, 1.0])
    values, events, peak = {}, {name: [] for name in modules}, 0.0
    periods = {name: MODULES[name][2] if name in MODULES else 5 for name in modules}
    sources = {"ctrl": {"qd": "traj.qd", "q": "arm.q"}, "jl": {"q": "arm.q"},
               "TrackingLost": {"e": "ctrl.e"}, "Saturated": {"tau": "ctrl.tau"},
               "ArmReadyMeasured": {"qdot": "arm.qdot"}, "Tracked": {"q": "arm.q"}}
    for module in modules.values():
        module.init()
    for tick in range(int(seconds * 1000) + 1):
        t = tick / 1000
        values["arm.q"], values["arm.qdot"] = physics.read("q"), physics.read("qdot")
        if adjust_at is not None and tick == adjust_at:
            modules["ctrl"].set_param("kp", 200.0)  # exception Saturated : adjust ctrl.kp
        for name, module in modules.items():
            if tick % periods[name]:
                continue
            inputs = {port: values.get(src) for port, src in sources.get(name, {}).items()}
            for port, value in module.compute(t, inputs).items():
                values[f"{name}.{port}"] = value
                if port == "event" and value:
                    events[name].append(t)
        if "ctrl.tau" in values:
            physics.write("tau", values["ctrl.tau"])
            peak = max(peak, float(np.max(np.abs(values["ctrl.e"]))))
        physics.step()
    return peak, values, events


def test_track_pid_runs_from_the_registries(track_pid):
    context, modules = track_pid
    peak, values, events = run(context, modules, 4.0)
    assert peak < 0.05
    assert events["jl"] == [] and events["TrackingLost"] == [] and events["Saturated"] == []
    assert events["ArmReadyMeasured"][0] == 0.0  # starts at rest: the pre-condition holds
    assert events["Tracked"] == []  # PID ends 35 mrad off at T: the post-condition fails
    assert values["Tracked.value"] == pytest.approx(abs(values["ctrl.e"]).max(), abs=2e-3)


def test_with_computed_torque_the_post_condition_holds_at_t(host):
    context, modules = build(host, ("computed_torque", {"kp": 400.0, "kv": 40.0}))
    peak, _, events = run(context, modules, 4.0)
    assert peak < 0.005
    assert events["Tracked"] == [4.0]


def test_adjusting_the_gain_during_the_task(track_pid):
    context, modules = track_pid
    peak, _, _ = run(context, modules, 1.0, adjust_at=500)
    assert modules["ctrl"].params["kp"] == 200.0
    assert peak < 0.1
