// ABRO, the classic of synchronous programming (Berry): emit O as soon as both A and B
// have been seen, in any order or together; R resets the behaviour.
mission ABRO {
    input A, B, R;
    output O;
    loop {
        par { await A; } || { await B; }
        emit O;
        halt;
    } each R;
}
property ABRO.o_needs_a: always (O -> once A);
property ABRO.o_needs_b: always (O -> once B);
property ABRO.r_silences_o: never (R and O);
