// A retried task: counters (repeat) and a caught type-2 exception.
robot arm : arm3dof;

robottask Track() on arm {
    duration 2 s;
    task_function joint_tracking(trajectory = cosine(q0 = [0.5, 0.5, 0.5], omega = pi));
    law pid(kp = 400.0, kv = 40.0);
    module traj : trajectory          period 1 ms wcet 0.1 ms on cpu0 priority 2;
    module ctrl : control_law         period 1 ms wcet 0.3 ms on cpu0 priority 1;
    module jl   : joint_limits(margin = 0.05) period 5 ms wcet 0.05 ms on cpu0 priority 3;
    connect traj.qd     -> ctrl.qd;
    connect traj.qd_dot -> ctrl.qd_dot;
    connect arm.q       -> ctrl.q;
    connect arm.qdot    -> ctrl.qdot;
    connect ctrl.tau    -> arm.tau;
    connect arm.q       -> jl.q;
    exception JointLimit from jl : fatal;
    exception TrackingLost from tracking_error(max = 0.2) : abort;
}

mission Retry {
    output Again, Done;
    repeat 2 {
        try {
            run Track();
        } catch TrackingLost {
            emit Again;
        }
    }
    emit Done;
}
property Retry.holds_done_after_track: always (Done -> once started(Track));
property Retry.holds_again_after_active: always (Again -> previously active(Track));
property Retry.holds_ends: eventually (Done or aborted);
property Retry.holds_never_failed: never failed;
property Retry.fails_never_again: never Again;
property Retry.fails_done: eventually Done;
