// Translated from HipHop's test suite: github.com/manuel-serrano/hiphop, test/p17.strl
// (Esterel v5 source) with its published trace test/p17.in / test/p17.out (commit ff9a3850).
mission P17 {
    output O;
    loop { signal S1 { if S1 { emit O; } pause; emit S1; } }
}
