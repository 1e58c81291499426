// Translated from HipHop's test suite: github.com/manuel-serrano/hiphop, test/every-immediate.strl
// (Esterel v5 source) with its published trace test/every-immediate.in / test/every-immediate.out (commit ff9a3850).
mission everyimmediate {
    input I;
    output O;
    every immediate I { emit O; }
}
