// Two Robot-Tasks in sequence on one robot: the hand-over.
robot arm : arm3dof;

robottask Approach() on arm {
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

robottask Grasp() on arm {
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

mission Handover {
    output Done;
    run Approach();
    run Grasp();
    emit Done;
}
property Handover.holds_handover: always (started(Grasp) -> once ended(Approach));
property Handover.holds_exclusive: never (active(Approach) and active(Grasp));
property Handover.holds_done_after_grasp: always (Done -> once ended(Grasp));
property Handover.holds_terminates: eventually (done or failed or aborted);
property Handover.holds_raise_ends: always (raised(TrackingLost) -> (failed or aborted));
property Handover.fails_always_done: eventually done;
property Handover.fails_raise_fails: always (raised(TrackingLost) -> failed);
property Handover.fails_grasp_ends: always (started(Grasp) -> eventually ended(Grasp));
