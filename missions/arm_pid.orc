// RR-1801 §7.1: joint-space PID tracking of the cosine trajectory
//     q_d(t) = q0 (1 + cos(pi t)),  q0 = [0.5, 0.5, 0.5] rad
// on the 3-DOF direct-drive arm. A joint-limit observer raises a type-3 (fatal) exception; a
// tracking-error observer a type-2 one; torque saturation lowers the gain (type 1).
robot arm : arm3dof;

robottask TrackPID(q0: vector = [0.5, 0.5, 0.5], kp: float = 400.0, kv: float = 40.0) on arm {
    duration 4 s;
    task_function joint_tracking(trajectory = cosine(q0 = q0, omega = pi));
    law pid(kp = kp, kv = kv, ki = 10.0);

    module traj : trajectory          period 1 ms wcet 0.1 ms on cpu0 priority 2;
    module ctrl : control_law         period 1 ms wcet 0.3 ms on cpu0 priority 1;
    module jl   : joint_limits(margin = 0.05) period 5 ms wcet 0.05 ms on cpu0 priority 3;
    connect traj.qd     -> ctrl.qd     : asyn/asyn;
    connect traj.qd_dot -> ctrl.qd_dot : asyn/asyn;
    connect arm.q       -> ctrl.q      : asyn/asyn;
    connect arm.qdot    -> ctrl.qdot   : asyn/asyn;
    connect ctrl.tau    -> arm.tau     : asyn/asyn;
    connect arm.q       -> jl.q        : asyn/asyn;

    exception JointLimit from jl : fatal;
    exception TrackingLost from tracking_error(max = 0.2) : abort;
    exception Saturated from torque_saturation : adjust ctrl.kp = 200.0;
}

mission ArmPID {
    output Tracked;
    run TrackPID();
    emit Tracked;
}
property ArmPID.tracked_at_good_end: always (Tracked <-> ended(TrackPID));
property ArmPID.terminates: eventually (done or failed or aborted);
property ArmPID.fatal_aborts: always (raised(JointLimit) -> aborted);
// Signal properties (docs/signal-properties.md): judged on runs and campaigns, not proved.
property ArmPID.at_rest_at_end: always (ended(TrackPID) -> norm(arm.qdot) < 0.1);
property ArmPID.shoulder_in_range: always (arm.q[0] > -0.1 and arm.q[0] < 1.1);
property ArmPID.tracking_bound: always (norm(arm.e) < 0.05);
