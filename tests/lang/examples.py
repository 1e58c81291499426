"""The examples of docs/language.md, for the lang tests."""

DECLARATIONS = """\
robot arm : arm3dof;                          // a physical resource, of a type a plugin provides
robot auv : auv(battery_wh = 400.0);          // with type parameters

input Start, Stop, Leak;                      // signals from the environment or the operator
input Battery : float;                        // a valued signal
output Done, Alarm : string;
"""

TRACK_PID = """\
robottask TrackPID(q0: vector = [0.5, 0.5, 0.5], kp: float = 400.0) on arm {
    duration 4 s;                                             // nominal duration T: good end at T
    task_function joint_tracking(trajectory = cosine(q0 = q0, omega = pi));
    law pid(kp = kp, kv = 40.0, ki = 10.0);

    // the time-constrained specification; omitted parts take the law's defaults
    module traj : trajectory        period 2 ms wcet 0.3 ms on cpu0 priority 2;
    module ctrl : control_law       period 1 ms wcet 0.5 ms on cpu0 priority 1;
    module jl   : joint_limits(margin = 0.1) period 5 ms wcet 0.1 ms on cpu0 priority 3;
    connect traj.qd -> ctrl.qd : asyn/syn;
    connect arm.q   -> ctrl.q  : asyn/asyn;
    connect ctrl.tau -> arm.tau : asyn/asyn;
    connect arm.q   -> jl.q    : asyn/asyn;

    precondition ArmReady;                                    // synchronization pre-condition
    precondition measure at_rest(tol = 0.01) within 2 s;      // measurement pre-condition + watchdog
    exception JointLimit from jl : fatal;                     // type 3
    exception TrackingLost from tracking_error(max = 0.2) : abort;        // type 2
    exception Saturated from torque_saturation : adjust ctrl.kp = 200.0; // type 1
    postcondition measure at_goal(tol = 0.005);               // measurement post-condition
    postcondition emit Tracked;                               // synchronization post-condition
}
"""

ARM_DEMO = """\
mission ArmDemo {
    output Done;
    run Home();
    repeat 3 {
        try {
            run TrackPID(kp = 600.0) within 10 s;
        } catch TrackingLost {
            run Home();
        }
    }
    emit Done;
}
"""

ABRO = """\
mission ABRO {
    input A, B, R;
    output O;
    loop {
        par { await A; } || { await B; }
        emit O;
        halt;
    } each R;
}
"""

PROPERTIES = """\
property ArmDemo.no_overlap: always not (active(TrackPID) and active(Home));
property ArmDemo.recovers:   always (raised(TrackingLost) -> eventually started(Home));
property ABRO.o_needs_a:     always (O -> once A);
"""

#: A Robot-Task the examples run but the reference does not show.
HOME = "robottask Home() on arm { duration 2 s; law pid(kp = 100.0); }\n"

#: Every example in one file that checks: the file-level ``output Done`` of DECLARATIONS
#: would clash with ArmDemo's own, so that line declares only Alarm here.
WHOLE_FILE = (DECLARATIONS.replace("output Done, Alarm : string;", "output Alarm : string;")
              + TRACK_PID + HOME + ARM_DEMO + ABRO + PROPERTIES)

ALL = {"declarations": DECLARATIONS, "track_pid": TRACK_PID, "arm_demo": ARM_DEMO,
       "abro": ABRO, "properties": PROPERTIES}
