// Suspension and strong/weak preemption.
mission Frozen {
    input T, H, K;
    output Out, Killed;
    abort {
        suspend {
            loop { await T; emit Out; }
        } when H;
    } when K do {
        emit Killed;
    }
}
property Frozen.holds_frozen: always (Out -> not H);
property Frozen.holds_killed_once: always (Killed -> previously historically not Killed);
property Frozen.holds_no_out_after_kill: always (Killed -> always not Out);
property Frozen.fails_out_on_t: always (T -> Out);
property Frozen.fails_no_kill: never Killed;
