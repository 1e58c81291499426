// Parking, a reusable sub-mission for the 3-DOF arm: bring the arm to rest at q = 0 from
// wherever it is, moving or not (no pre-condition: it takes over at once from an aborted
// task). Use it with
//     from "lib/parking.orc" import Parking;   ...   run mission Parking;
// Runs alone too: orccad run missions/lib/parking.orc
robot arm : arm3dof;

mission Parking {
    run Park();
}

// Park's Module-Tasks are the law's defaults (traj and ctrl, wired by name: min_jerk starts
// from the measured position).
robottask Park(goal: vector = [0.0, 0.0, 0.0]) on arm {
    duration 2 s;
    task_function joint_tracking(trajectory = min_jerk(goal = goal, duration = 1.5));
    law pid(kp = 400.0, kv = 40.0, ki = 10.0);
}
