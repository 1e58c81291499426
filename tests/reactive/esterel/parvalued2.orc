// Translated from HipHop's test suite: github.com/manuel-serrano/hiphop, test/parvalued2.strl
// (Esterel v5 source) with its published trace test/parvalued2.in / test/parvalued2.out (commit ff9a3850).
mission parvalued2 {
    output J : int;
    signal I : int { par { emit I(5); } || { if I { emit J(?I); } } }
}
