// RR-1801 §6.2's question on the paper's trajectory q_d(t) = q0 (1 + cos(pi t)): computed
// torque split into Module-Tasks at two rates. The feedback path (PD on the error, then
// tau = M(q) u + N(q, qdot) with the latest model) runs every 1 ms; the dynamic model (M, N
// from Pinocchio on the same MJCF file MuJoCo simulates) only every 10 ms, on its own
// processor across the bus. `python bench/timing_table.py --multirate` sweeps the model's
// period (docs/control.md).
robot arm : arm3dof;

robottask TrackCTMultirate(q0: vector = [0.5, 0.5, 0.5], kp: float = 400.0,
                           kv: float = 40.0) on arm {
    duration 4 s;
    task_function joint_tracking(trajectory = cosine(q0 = q0, omega = pi));

    module traj  : trajectory                  period 1 ms  wcet 0.1 ms  on cpu0 priority 2;
    module ctrl  : ct_feedback(kp = kp, kv = kv) period 1 ms  wcet 0.2 ms  on cpu0 priority 1;
    module model : dynamic_model               period 10 ms wcet 2 ms    on cpu1 priority 1;
    module jl    : joint_limits(margin = 0.05)  period 5 ms  wcet 0.05 ms on cpu0 priority 3;
    connect traj.qd      -> ctrl.qd      : asyn/asyn;
    connect traj.qd_dot  -> ctrl.qd_dot  : asyn/asyn;
    connect traj.qd_ddot -> ctrl.qd_ddot : asyn/asyn;
    connect arm.q        -> ctrl.q       : asyn/asyn;
    connect arm.qdot     -> ctrl.qdot    : asyn/asyn;
    connect arm.q        -> model.q      : asyn/asyn;
    connect arm.qdot     -> model.qdot   : asyn/asyn;
    connect model.M      -> ctrl.M       : asyn/asyn;
    connect model.N      -> ctrl.N       : asyn/asyn;
    connect ctrl.tau     -> arm.tau      : asyn/asyn;
    connect arm.q        -> jl.q         : asyn/asyn;

    exception JointLimit from jl : fatal;
    exception TrackingLost from tracking_error(max = 0.2) : abort;
}

mission ArmComputedTorqueMultirate {
    output Tracked;
    run TrackCTMultirate();
    emit Tracked;
}
property ArmComputedTorqueMultirate.tracked_at_good_end:
    always (Tracked <-> ended(TrackCTMultirate));
property ArmComputedTorqueMultirate.terminates: eventually (done or failed or aborted);
// Signal properties (docs/signal-properties.md): judged on runs and campaigns, not proved.
property ArmComputedTorqueMultirate.tracking_bound: always (norm(arm.e) < 0.01);
property ArmComputedTorqueMultirate.shoulder_in_range:
    always (arm.q[0] > -0.1 and arm.q[0] < 1.1);
