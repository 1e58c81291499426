// A mission that uses every statement class, with recovery paths, on the 3-DOF arm, and
// two reusable sub-missions of missions/lib/.
//
// Home, then track the cosine trajectory; a lost track or a time-out is retried after
// re-homing, at most three times; the operator may hold (suspend) or stop the mission: Stop
// aborts the tracking (or the re-homing), parks the arm (Park runs to its end: the mission
// finishes only then) and 0.5 s after Stop emits Stopping; a joint-limit violation is fatal
// and 'on fatal' reports it.
from "lib/homing.orc" import Homing;    // run Home (to the cosine's start), lib/homing.orc
from "lib/parking.orc" import Parking;  // run Park (to rest at q = 0), lib/parking.orc

robot arm : arm3dof;

input Stop, Hold, Gripper : float;
output Started, Beat, Retry : int, GaveUp, Finished, Grip : float, Fatal, Stopping;

robottask TrackPID(q0: vector = [0.5, 0.5, 0.5], kp: float = 400.0) on arm {
    duration 4 s;
    task_function joint_tracking(trajectory = cosine(q0 = q0, omega = pi));
    law pid(kp = kp, kv = 40.0, ki = 10.0);
    module traj : trajectory  period 1 ms wcet 0.1 ms on cpu0 priority 2;
    module ctrl : control_law period 1 ms wcet 0.3 ms on cpu0 priority 1;
    module jl   : joint_limits(margin = 0.05) period 5 ms wcet 0.05 ms on cpu0 priority 3;
    connect traj.qd     -> ctrl.qd;
    connect traj.qd_dot -> ctrl.qd_dot;
    connect arm.q       -> ctrl.q;
    connect arm.qdot    -> ctrl.qdot;
    connect ctrl.tau    -> arm.tau;
    connect arm.q       -> jl.q;
    exception JointLimit from jl : fatal;
    exception TrackingLost from tracking_error(max = 0.2) : abort;
    exception Saturated from torque_saturation : adjust ctrl.kp = 200.0;
}

mission ArmRecovery {
    emit Started;
    run mission Homing;
    var tries := 0;
    signal Tracked {
        race {
            sustain Beat;                              // a heartbeat while the mission runs
        } || {
            weak abort {
                suspend {
                    trap Success {
                        repeat 3 {
                            try {
                                run TrackPID(kp = 600.0) within 10 s;
                                emit Tracked;
                                exit Success;
                            } catch TrackingLost, Timeout {
                                tries := tries + 1;
                                emit Retry(tries);
                                run mission Homing;
                            }
                        }
                        emit GaveUp;
                    } handle {
                        nothing;
                    }
                } when Hold;
            } when Stop do {
                run mission Parking;                   // park the arm, then finish
            }
        } || {
            loop {
                await Gripper;
                if ?Gripper > 0.5 { emit Grip(?Gripper); } else { pause; }
            } each Stop;
        } || {
            await immediate Tracked;
            await 2 Beat;
            every 1 s { pause; }
        } || {
            abort { halt; } when immediate Stop;
            await 0.5 s;
            par { emit Stopping; } || { await (Hold or not Hold); }
            halt;                                      // the park ends the race, not this
        }
    }
    emit Finished;
    on fatal {
        emit Fatal;
    }
}
property ArmRecovery.home_before_tracking: always (started(TrackPID) -> once ended(Home));
property ArmRecovery.one_task_at_a_time: never (active(TrackPID) and active(Home));
property ArmRecovery.retry_after_a_loss: always (Retry -> once (raised(TrackingLost) or raised(Timeout)));
property ArmRecovery.fatal_reported: always (aborted -> Fatal);
property ArmRecovery.park_completes: always (started(Park) -> eventually ended(Park));
property ArmRecovery.parked_before_done: always (done -> not previously active(Park) or ended(Park));
property ArmRecovery.finished_once: always (Finished -> previously historically not Finished);
