// ABRO: emit O once both A and B have been seen; R resets.
mission ABRO {
    input A, B, R;
    output O;
    loop {
        par { await A; } || { await B; }
        emit O;
        halt;
    } each R;
}
property ABRO.holds_o_needs_a: always (O -> once A);
property ABRO.holds_o_needs_b: always (O -> once B);
property ABRO.holds_no_o_on_r: never (R and O);
property ABRO.holds_o_once_per_r: always (O -> previously (not O since R) or previously historically not O);
property ABRO.fails_o_prev_a: always (O -> previously A);
property ABRO.fails_live: always ((A and B) -> eventually O);
property ABRO.fails_never_o: never O;
property ABRO.fails_o_infinitely: always eventually O;
