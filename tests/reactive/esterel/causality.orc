// Translated from HipHop's test suite: github.com/manuel-serrano/hiphop, test/causality.strl
// (Esterel v5 source) with its published trace test/causality.in / test/causality.out (commit ff9a3850).
mission presentemit {
    output I, O;
    loop { if O { emit I; } pause; emit O; }
}
