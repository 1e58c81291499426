// Translated from HipHop's test suite: github.com/manuel-serrano/hiphop, test/run.strl
// (Esterel v5 source) with its published trace test/run.in / test/run.out (commit ff9a3850).
mission m1 [input T, W; output V, Z] {
    par { if T { emit V; } } || { if W { emit Z; } }
}
mission run2 {
    input S, U;
    output A, B;
    run mission m1 [T / S, W / U, V / A, Z / B];
}
