// Translated from HipHop's test suite: github.com/manuel-serrano/hiphop, test/every-delay.strl
// (Esterel v5 source) with its published trace test/every-delay.in / test/every-delay.out (commit ff9a3850).
mission everydelay {
    input I;
    output O;
    every 2 I { emit O; }
}
