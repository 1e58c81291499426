// Timers (time diverges: an awaited duration elapses) and an environment assumption.
mission Timers {
    input Go;
    output Tick, Done;
    await 1 s;
    emit Tick;
    await Go;
    emit Done;
}
property Timers.holds_tick: eventually Tick;
property Timers.holds_done_after_tick: always (Done -> previously once Tick);
property Timers.fails_done: eventually Done;
property Timers.fails_tick_first_instant: Tick;

mission Assumed {
    input Go;
    output Done;
    await 2 Go;
    emit Done;
}
assume Assumed.go_often: always eventually Go;
property Assumed.holds_done: eventually Done;
property Assumed.holds_two_go: always (Done -> (Go and previously once Go));
property Assumed.fails_done_soon: always (Go -> Done);
