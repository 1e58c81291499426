// Translated from HipHop's test suite: github.com/manuel-serrano/hiphop, test/example-parallel2.strl
// (Esterel v5 source) with its published trace test/example-parallel2.in / test/example-parallel2.out (commit ff9a3850).
mission parallel2 {
    output J;
    signal I { par { if I { emit J; } } || { emit I; } }
}
