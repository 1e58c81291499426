robot arm : arm3dof;
// RR-1801 §3.4.4: one measurement pre-condition, one type-1 and one type-2 exception, one
// measurement post-condition ("3 states and 16 transitions" in 1992). See docs/robot-tasks.md.
robottask Paper() on arm {
    task_function joint_tracking(trajectory = cosine(q0 = [0.5, 0.5, 0.5], omega = pi));
    law pid(kp = 400.0, kv = 40.0);
    module traj : trajectory;
    module ctrl : control_law;
    connect traj.qd -> ctrl.qd;
    connect arm.q -> ctrl.q;
    connect arm.qdot -> ctrl.qdot;
    connect ctrl.tau -> arm.tau;
    precondition measure at_rest(tol = 0.01);
    exception Saturated from torque_saturation : adjust ctrl.kp = 200.0;
    exception TrackingLost from tracking_error(max = 0.2) : abort;
    postcondition measure at_goal(tol = 0.005, goal = [1.0, 1.0, 1.0]);
}
