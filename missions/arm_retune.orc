// Type-1 exceptions that compute (RR-1801 §3.4.2: "the control gain k may be increased upto a
// maximal authorized value", a parameter "progressively set"): a PID started with soft gains
// on the cosine trajectory of §7.1 retunes itself while it runs.
//
// - Drift: every 50 ms while the tracking error exceeds 0.02 rad, kp is multiplied by 1.5,
//   at most kmax: 100, 150, 225, 337.5, 506.25, 759.375, then 800 each time;
// - Lagging: the first time the error exceeds 0.04 rad, the integral gain ki goes from 0 to
//   20 over 1 s (set at every 1 ms release of ctrl);
// - a lost track (0.2 rad) is still a type-2 exception.
//
// orccad run missions/arm_retune.orc lists every update with its old and new value.
robot arm : arm3dof;

robottask TrackSoft(q0: vector = [0.5, 0.5, 0.5], kmax: float = 800.0) on arm {
    duration 3 s;
    task_function joint_tracking(trajectory = cosine(q0 = q0, omega = pi));
    law pid(kp = 100.0, kv = 20.0, ki = 0.0);
    module traj : trajectory  period 1 ms wcet 0.1 ms on cpu0 priority 2;
    module ctrl : control_law period 1 ms wcet 0.3 ms on cpu0 priority 1;
    module err  : tracking_error(max = 0.02) period 50 ms wcet 0.05 ms on cpu0 priority 3;
    connect traj.qd     -> ctrl.qd;
    connect traj.qd_dot -> ctrl.qd_dot;
    connect arm.q       -> ctrl.q;
    connect arm.qdot    -> ctrl.qdot;
    connect ctrl.tau    -> arm.tau;
    connect ctrl.e      -> err.e;
    exception Drift from err : adjust ctrl.kp = min(ctrl.kp * 1.5, kmax);
    exception Lagging from tracking_error(max = 0.04, edge = true) : adjust ctrl.ki = ramp(0.0, 20.0, 1 s);
    exception TrackingLost from tracking_error(max = 0.2) : abort;
}

mission ArmRetune {
    output Tracked;
    run TrackSoft();
    emit Tracked;
}
property ArmRetune.tracked_at_good_end: always (Tracked <-> ended(TrackSoft));
property ArmRetune.terminates: eventually (done or failed or aborted);
