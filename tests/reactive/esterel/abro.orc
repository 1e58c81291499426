// Translated from HipHop's test suite: github.com/manuel-serrano/hiphop, test/abro.strl
// (Esterel v5 source) with its published trace test/abro.in / test/abro.out (commit ff9a3850).
mission ABRO {
    input A, B, R;
    output O;
    loop { par { await A; } || { await B; } emit O; } each R;
}
