// A mission whose designer got a property wrong: `orccad check` exits 1 and prints a
// counterexample script that `orccad react --composed` replays to the violation.
//
// The approach is tried once; a lost track is caught and the mission places anyway, so
// "placed only after a completed approach" is false. And nothing forces the operator to
// press Go, so "eventually placed" is false too (a run that waits forever).
robot arm : arm3dof;

input Go;
output Placed;

robottask Approach() on arm {
    duration 2 s;
    task_function joint_tracking(trajectory = cosine(q0 = [0.5, 0.5, 0.5], omega = pi));
    law pid(kp = 400.0, kv = 40.0);
    module traj : trajectory  period 1 ms wcet 0.1 ms on cpu0 priority 2;
    module ctrl : control_law period 1 ms wcet 0.3 ms on cpu0 priority 1;
    connect traj.qd     -> ctrl.qd;
    connect traj.qd_dot -> ctrl.qd_dot;
    connect arm.q       -> ctrl.q;
    connect arm.qdot    -> ctrl.qdot;
    connect ctrl.tau    -> arm.tau;
    exception TrackingLost from tracking_error(max = 0.2) : abort;
}

robottask Place() on arm {
    duration 1 s;
    task_function joint_tracking(trajectory = constant(value = [0.0, 0.5, 0.0]));
    law pid(kp = 400.0, kv = 40.0);
    module traj : trajectory  period 1 ms wcet 0.1 ms on cpu0 priority 2;
    module ctrl : control_law period 1 ms wcet 0.3 ms on cpu0 priority 1;
    connect traj.qd     -> ctrl.qd;
    connect traj.qd_dot -> ctrl.qd_dot;
    connect arm.q       -> ctrl.q;
    connect arm.qdot    -> ctrl.qdot;
    connect ctrl.tau    -> arm.tau;
}

mission PickPlace {
    await Go;
    try {
        run Approach();
    } catch TrackingLost {
        nothing;
    }
    run Place();
    emit Placed;
}

property PickPlace.placed_after_approach: always (Placed -> once ended(Approach));
property PickPlace.eventually_placed: eventually Placed;
property PickPlace.one_task_at_a_time: never (active(Approach) and active(Place));
