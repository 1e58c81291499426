// Translated from HipHop's test suite: github.com/manuel-serrano/hiphop, test/prepure2.strl
// (Esterel v5 source) with its published trace test/prepure2.in / test/prepure2.out (commit ff9a3850).
mission prepure2 {
    output O1, O2;
    signal S { loop { if pre(S) { emit O1; } else { emit O2; } pause; emit S; } }
}
