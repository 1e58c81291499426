// The AUV visits the waypoints it receives as valued inputs (docs/auv.md): each Waypoint
// [x, y, depth] is handed to the GoTo Robot-Task as a run-time argument, evaluated in the
// instant the task starts; once there, the vehicle holds station until the next one.
//
// - a new Waypoint re-targets the vehicle at once (the current GoTo or Hold is aborted);
// - a waypoint not reached within 120 s (Timeout) or a low battery ends the tour;
// - Home ends the tour: the vehicle surfaces where it is;
// - a leak or the depth limit (type 3): the mission is aborted and 'on fatal' surfaces.
// A waypoint the tasks refuse (a depth < 0, not 3 components) ends the run 'failed' with
// the argument's location.
//
//   orccad run missions/auv_waypoints.orc --inject 'Waypoint([15, 0, 5])@1' \
//       'Waypoint([15, 12, 8])@40' 'Waypoint([0, 12, 5])@80' Home@120
robot auv : auv;

input Waypoint : vector;        // [x, y, depth] [m]
input Home;                     // end the tour
output Reached : int;           // waypoints reached so far

robottask GoTo(target: vector = [10.0, 0.0, 10.0]) on auv {
    module guide : waypoint_guidance(target = target) period 100 ms wcet 1 ms on cpu0 priority 2;
    module pilot : auv_autopilot period 50 ms wcet 1 ms on cpu0 priority 1;
    connect auv.position  -> guide.position;
    connect auv.attitude  -> guide.attitude;
    connect guide.setpoint -> pilot.setpoint;
    connect auv.depth     -> pilot.depth;
    connect auv.attitude  -> pilot.attitude;
    connect auv.velocity  -> pilot.velocity;
    connect pilot.tau     -> auv.tau;
    postcondition measure at_waypoint(tol = 1.5);
    exception Leak from leak : fatal;
    exception DepthLimit from depth_limit(max = 30.0) : fatal;
    exception BatteryLow from battery_low(min = 20.0) : abort;
}

// Station keeping at the waypoint reached, until killed (no good end).
robottask Hold(target: vector = [10.0, 0.0, 10.0]) on auv {
    module guide : hold_guidance(target = target) period 100 ms wcet 1 ms on cpu0 priority 2;
    module pilot : auv_autopilot period 50 ms wcet 1 ms on cpu0 priority 1;
    connect auv.position  -> guide.position;
    connect auv.attitude  -> guide.attitude;
    connect guide.setpoint -> pilot.setpoint;
    connect auv.depth     -> pilot.depth;
    connect auv.attitude  -> pilot.attitude;
    connect auv.velocity  -> pilot.velocity;
    connect pilot.tau     -> auv.tau;
    exception Leak from leak : fatal;
    exception DepthLimit from depth_limit(max = 30.0) : fatal;
    exception BatteryLow from battery_low(min = 20.0) : abort;
}

robottask Surface() on auv {
    module guide : depth_guidance(depth = 0.0) period 100 ms wcet 1 ms on cpu0 priority 2;
    module pilot : auv_autopilot period 50 ms wcet 1 ms on cpu0 priority 1;
    connect auv.position  -> guide.position;
    connect auv.attitude  -> guide.attitude;
    connect guide.setpoint -> pilot.setpoint;
    connect auv.depth     -> pilot.depth;
    connect auv.attitude  -> pilot.attitude;
    connect auv.velocity  -> pilot.velocity;
    connect pilot.tau     -> auv.tau;
    postcondition measure at_waypoint(tol = 0.3);
}

mission AuvWaypoints {
    var reached := 0;
    await Waypoint;                                   // the first waypoint
    try {
        abort {
            loop {
                abort {
                    run GoTo(target = ?Waypoint) within 120 s;
                    reached := reached + 1;
                    emit Reached(reached);
                    run Hold(target = ?Waypoint);     // until the next waypoint
                } when Waypoint;                      // a new waypoint: go there at once
            }
        } when Home;
    } catch BatteryLow, Timeout {
        nothing;                                      // end the tour: surface below
    }
    run Surface();
    on fatal {
        run Surface();
    }
}

property AuvWaypoints.leak_surfaces: always (raised(Leak) -> eventually ended(Surface));
property AuvWaypoints.surface_alone:
    always not (active(Surface) and (active(GoTo) or active(Hold)));
property AuvWaypoints.safe_depth: always (auv.depth < 30.0);
