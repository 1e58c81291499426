// Translated from HipHop's test suite: github.com/manuel-serrano/hiphop, test/parvalued.strl
// (Esterel v5 source) with its published trace test/parvalued.in / test/parvalued.out (commit ff9a3850).
mission parvalued {
    output J : int;
    signal I : int { par { if I { emit J(?I); } } || { emit I(5); } }
}
