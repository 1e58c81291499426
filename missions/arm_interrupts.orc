// RR-1801 §3.4.1: an observer "may be either periodic or activated under interruption".
// The PID tracking of missions/arm_pid.orc, watched by an interrupt-driven tracking-error
// observer on a second processor: each write of the task error by the control law (every
// 1 ms, arriving over the bus) interrupts it, but it runs at most every 2 ms (earlier
// interrupts are deferred and counted in the report). `orccad tcs` analyses it as a periodic
// Module-Task of period 2 ms. The Robot-Task's automaton reacts on cpu0, each reaction taking
// 0.05 ms there: the observer's TrackingLost signal crosses the bus (an `event` message, safe
// protocol) before the reaction that aborts the task (mission ArmInterruptsTight).
robot arm : arm3dof;

robottask TrackWatched(q0: vector = [0.5, 0.5, 0.5], kp: float = 400.0, kv: float = 40.0,
                       max_error: float = 0.2) on arm {
    duration 4 s;
    task_function joint_tracking(trajectory = cosine(q0 = q0, omega = pi));
    law pid(kp = kp, kv = kv, ki = 10.0);
    automaton on cpu0 reaction 0.05 ms;

    module traj  : trajectory  period 1 ms wcet 0.1 ms on cpu0 priority 2;
    module ctrl  : control_law period 1 ms wcet 0.3 ms on cpu0 priority 1;
    module watch : tracking_error(max = max_error)
                   sporadic min_interarrival 2 ms wcet 0.05 ms on cpu1 priority 1;
    connect traj.qd     -> ctrl.qd     : asyn/asyn;
    connect traj.qd_dot -> ctrl.qd_dot : asyn/asyn;
    connect arm.q       -> ctrl.q      : asyn/asyn;
    connect arm.qdot    -> ctrl.qdot   : asyn/asyn;
    connect ctrl.tau    -> arm.tau     : asyn/asyn;
    connect ctrl.e      -> watch.e     : asyn/asyn;

    exception TrackingLost from watch : abort;
}

mission ArmInterrupts {
    output Tracked, Lost;
    try {
        run TrackWatched();
        emit Tracked;
    } catch TrackingLost {
        emit Lost;
    }
}
// The same with a bound the PID exceeds (its error peaks at 0.045 rad): TrackingLost.
mission ArmInterruptsTight {
    output Tracked, Lost;
    try {
        run TrackWatched(max_error = 0.02);
        emit Tracked;
    } catch TrackingLost {
        emit Lost;
    }
}
property ArmInterrupts.terminates: eventually (done or failed or aborted);
property ArmInterrupts.tracked_or_lost: always (Tracked -> not Lost);
