// Translated from HipHop's test suite: github.com/manuel-serrano/hiphop, test/prepure.strl
// (Esterel v5 source) with its published trace test/prepure.in / test/prepure.out (commit ff9a3850).
mission prepure {
    output O1, O2;
    loop { signal S { if pre(S) { emit O1; } else { emit O2; } pause; emit S; } }
}
