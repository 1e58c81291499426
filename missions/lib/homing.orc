// Homing, a reusable sub-mission for the 3-DOF arm: bring the arm to the start of the cosine
// trajectory the tracking missions follow, q = [1, 1, 1] rad (q_d(0) = 2 q0 with q0 = 0.5),
// from wherever it is once it rests. Use it with
//     from "lib/homing.orc" import Homing;   ...   run mission Homing;
// Runs alone too: orccad run missions/lib/homing.orc
robot arm : arm3dof;

mission Homing {
    run Home();
}

// Home waits (at most 2 s) for the arm to be at rest, then moves it in 1 s (minimum jerk)
// and holds it there until its nominal duration ends.
robottask Home(goal: vector = [1.0, 1.0, 1.0]) on arm {
    duration 1.5 s;
    task_function joint_tracking(trajectory = min_jerk(goal = goal, duration = 1.0));
    law pid(kp = 400.0, kv = 40.0);
    module traj : trajectory  period 1 ms wcet 0.1 ms on cpu0 priority 2;
    module ctrl : control_law period 1 ms wcet 0.3 ms on cpu0 priority 1;
    connect arm.q       -> traj.q;          // min_jerk starts from the measured position
    connect traj.qd     -> ctrl.qd;
    connect traj.qd_dot -> ctrl.qd_dot;
    connect arm.q       -> ctrl.q;
    connect arm.qdot    -> ctrl.qdot;
    connect ctrl.tau    -> arm.tau;
    precondition measure at_rest(tol = 0.05) within 2 s;
}
