// Translated from HipHop's test suite: github.com/manuel-serrano/hiphop, test/run2.strl
// (Esterel v5 source) with its published trace test/run2.in / test/run2.out (commit ff9a3850).
mission m1 [input T, W; output V, Z] {
    par { if T { signal L { emit L; emit V; } } } || { if W { emit Z; } }
}
mission run22 {
    input S, U;
    output A, B;
    signal L { emit L; }
    run mission m1 [T / S, W / U, V / A, Z / B];
    run mission m1 [T / S, W / U, V / A, Z / B];
}
