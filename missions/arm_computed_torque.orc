// The trajectory of RR-1801 §7.1, q_d(t) = q0 (1 + cos(pi t)), tracked by computed torque
// with the arm's Pinocchio model (built from the same MJCF file MuJoCo simulates), with the
// same kp and kv as missions/arm_pid.orc: the model cancels the dynamics PID must fight.
robot arm : arm3dof;

robottask TrackCT(q0: vector = [0.5, 0.5, 0.5], kp: float = 400.0, kv: float = 40.0) on arm {
    duration 4 s;
    task_function joint_tracking(trajectory = cosine(q0 = q0, omega = pi));
    law computed_torque(kp = kp, kv = kv);

    module traj : trajectory          period 1 ms wcet 0.1 ms on cpu0 priority 2;
    module ctrl : control_law         period 1 ms wcet 0.4 ms on cpu0 priority 1;
    module jl   : joint_limits(margin = 0.05) period 5 ms wcet 0.05 ms on cpu0 priority 3;
    connect traj.qd      -> ctrl.qd      : asyn/asyn;
    connect traj.qd_dot  -> ctrl.qd_dot  : asyn/asyn;
    connect traj.qd_ddot -> ctrl.qd_ddot : asyn/asyn;
    connect arm.q        -> ctrl.q       : asyn/asyn;
    connect arm.qdot     -> ctrl.qdot    : asyn/asyn;
    connect ctrl.tau     -> arm.tau      : asyn/asyn;
    connect arm.q        -> jl.q         : asyn/asyn;

    exception JointLimit from jl : fatal;
    exception TrackingLost from tracking_error(max = 0.2) : abort;
}

mission ArmComputedTorque {
    output Tracked;
    run TrackCT();
    emit Tracked;
}
property ArmComputedTorque.tracked_at_good_end: always (Tracked <-> ended(TrackCT));
property ArmComputedTorque.terminates: eventually (done or failed or aborted);
// Signal properties (docs/signal-properties.md): judged on runs and campaigns, not proved.
property ArmComputedTorque.at_rest_at_end:
    always (ended(TrackCT) -> norm(arm.qdot) < 0.1);
property ArmComputedTorque.shoulder_in_range: always (arm.q[0] > -0.1 and arm.q[0] < 1.1);
property ArmComputedTorque.tracking_bound: always (norm(arm.e) < 0.05);
