// A type-3 exception and the on fatal block.
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

mission Fatal {
    output Alarm, Done;
    run Track();
    emit Done;
    on fatal {
        emit Alarm;
    }
}
property Fatal.holds_alarm_on_abort: always (aborted -> Alarm);
property Fatal.holds_fatal_aborts: always (raised(JointLimit) -> aborted);
property Fatal.holds_no_done_after_alarm: always (Alarm -> not eventually done);
property Fatal.fails_no_alarm: never Alarm;
