// Translated from HipHop's test suite: github.com/manuel-serrano/hiphop, test/loopeach.strl
// (Esterel v5 source) with its published trace test/loopeach.in / test/loopeach.out (commit ff9a3850).
mission loopeach {
    input I;
    output O;
    loop { emit O; } each I;
}
