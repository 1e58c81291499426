// Translated from HipHop's test suite: github.com/manuel-serrano/hiphop, test/every1.strl
// (Esterel v5 source) with its published trace test/every1.in / test/every1.out (commit ff9a3850).
mission every1 {
    input I;
    output O;
    every I { emit O; }
}
