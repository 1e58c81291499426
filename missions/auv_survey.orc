// RR-1801's second example: a survey by an autonomous underwater vehicle (docs/auv.md).
//
// Launch (a GPS fix, station keeping at the surface), dive, transit, lawnmower survey, surface,
// recover (a GPS fix, station keeping at the surface). Recovery paths:
// - too close to the seabed (AltitudeLow): climb to a safer depth and resume the survey there
//   (a second time: end the survey and surface);
// - low battery (BatteryLow): end the survey and surface; Recover then raises BatteryLow again
//   at the surface, so the mission ends 'failed' with that reason, the vehicle safe;
// - a leak or the depth limit (type 3): the mission is aborted and 'on fatal' surfaces at once.
from "lib/surfacing.orc" import Surfacing;  // Surface (to depth 0 m): lib/surfacing.orc

robot auv : auv;

output SurveyEnded;

// Station keeping at the surface once the GPS has a fix (watchdog: gps_fix_timeout).
robottask StationKeep(x: float = 0.0, y: float = 0.0) on auv {
    duration 5 s;
    module guide : station_guidance(x = x, y = y, depth = 0.0) period 100 ms wcet 1 ms on cpu0 priority 2;
    module pilot : auv_autopilot period 50 ms wcet 1 ms on cpu0 priority 1;
    connect auv.position  -> guide.position;
    connect auv.attitude  -> guide.attitude;
    connect guide.setpoint -> pilot.setpoint;
    connect auv.depth     -> pilot.depth;
    connect auv.attitude  -> pilot.attitude;
    connect auv.velocity  -> pilot.velocity;
    connect pilot.tau     -> auv.tau;
    precondition measure gps_fix(acquire = 2.0) within 30 s;
    exception BatteryLow from battery_low(min = 20.0) : abort;
}

robottask Dive(depth: float = 15.0) on auv {
    module guide : depth_guidance(depth = depth) period 100 ms wcet 1 ms on cpu0 priority 2;
    module pilot : auv_autopilot period 50 ms wcet 1 ms on cpu0 priority 1;
    connect auv.position  -> guide.position;
    connect auv.attitude  -> guide.attitude;
    connect guide.setpoint -> pilot.setpoint;
    connect auv.depth     -> pilot.depth;
    connect auv.attitude  -> pilot.attitude;
    connect auv.velocity  -> pilot.velocity;
    connect pilot.tau     -> auv.tau;
    postcondition measure at_waypoint(tol = 0.5);
    exception Leak from leak : fatal;
    exception DepthLimit from depth_limit(max = 30.0) : fatal;
    exception BatteryLow from battery_low(min = 20.0) : abort;
}

robottask GoTo(x: float = 0.0, y: float = 0.0, depth: float = 15.0) on auv {
    module guide : los_guidance(x = x, y = y, depth = depth) period 100 ms wcet 1 ms on cpu0 priority 2;
    module pilot : auv_autopilot period 50 ms wcet 1 ms on cpu0 priority 1;
    connect auv.position  -> guide.position;
    connect auv.attitude  -> guide.attitude;
    connect guide.setpoint -> pilot.setpoint;
    connect auv.depth     -> pilot.depth;
    connect auv.attitude  -> pilot.attitude;
    connect auv.velocity  -> pilot.velocity;
    connect pilot.tau     -> auv.tau;
    postcondition measure at_waypoint(tol = 2.0);
    exception Leak from leak : fatal;
    exception DepthLimit from depth_limit(max = 30.0) : fatal;
    exception BatteryLow from battery_low(min = 20.0) : abort;
    exception AltitudeLow from altitude_low(min = 5.0) : abort;
}

robottask Survey(depth: float = 15.0) on auv {
    module guide : lawnmower_guidance(area = [10.0, 0.0, 50.0, 20.0], spacing = 10.0, depth = depth) period 100 ms wcet 1 ms on cpu0 priority 2;
    module pilot : auv_autopilot period 50 ms wcet 1 ms on cpu0 priority 1;
    connect auv.position  -> guide.position;
    connect auv.attitude  -> guide.attitude;
    connect guide.setpoint -> pilot.setpoint;
    connect auv.depth     -> pilot.depth;
    connect auv.attitude  -> pilot.attitude;
    connect auv.velocity  -> pilot.velocity;
    connect pilot.tau     -> auv.tau;
    postcondition measure at_waypoint(tol = 2.0);
    exception Leak from leak : fatal;
    exception DepthLimit from depth_limit(max = 30.0) : fatal;
    exception BatteryLow from battery_low(min = 20.0) : abort;
    exception AltitudeLow from altitude_low(min = 5.0) : abort;
}

mission AuvSurvey {
    run StationKeep();                                // launch
    try {
        run Dive(depth = 15.0);
        try {
            run GoTo(x = 10.0, y = 0.0, depth = 15.0);
            run Survey(depth = 15.0);
        } catch AltitudeLow {
            run Dive(depth = 8.0);                    // climb away from the seabed
            run Survey(depth = 8.0);                  // resume from the nearest lane point
        }
        emit SurveyEnded;
    } catch BatteryLow, AltitudeLow {
        nothing;                                      // end the survey: surface below
    }
    run mission Surfacing;
    run StationKeep(x = 50.0, y = 20.0);              // recover (fails if the battery is low)
    on fatal {
        run mission Surfacing;
    }
}

property AuvSurvey.leak_surfaces: always (raised(Leak) -> eventually ended(Surface));
property AuvSurvey.depth_limit_surfaces: always (raised(DepthLimit) -> eventually ended(Surface));
property AuvSurvey.no_dive_after_depth_limit:
    always (raised(DepthLimit) -> always not (started(Dive) or started(GoTo) or started(Survey)));
property AuvSurvey.battery_low_surfaces:
    always ((raised(BatteryLow) and once started(Dive))
            -> (once ended(Surface) or eventually ended(Surface)));
property AuvSurvey.failed_only_at_surface:
    always (failed -> (not once started(Dive) or once ended(Surface)));
property AuvSurvey.surface_alone:
    always not (active(Surface) and (active(Dive) or active(GoTo) or active(Survey)));
// Signal properties (docs/signal-properties.md): judged on runs and campaigns, not proved.
property AuvSurvey.safe_depth: always (auv.depth < 30.0);
property AuvSurvey.clear_of_seabed: always (auv.altitude > 2.0);
