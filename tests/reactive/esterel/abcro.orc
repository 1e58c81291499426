// Translated from HipHop's test suite: github.com/manuel-serrano/hiphop, test/abcro.strl
// (Esterel v5 source) with its published trace test/abcro.in / test/abcro.out (commit ff9a3850).
mission ABCRO {
    input A, B, C, R;
    output O;
    loop { par { await A; } || { await B; } || { await C; } emit O; } each R;
}
