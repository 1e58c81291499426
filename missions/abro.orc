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
