// Surfacing, a reusable sub-mission for the AUV: climb to the surface (depth 0 m) and end
// there. It has no exception: it is what every recovery path ends with. Use it with
//     from "lib/surfacing.orc" import Surfacing;   ...   run mission Surfacing;
// Runs alone too: orccad run missions/lib/surfacing.orc
robot auv : auv;

mission Surfacing {
    run Surface();
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
