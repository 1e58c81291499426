// Translated from HipHop's test suite: github.com/manuel-serrano/hiphop, test/example-parallel.strl
// (Esterel v5 source) with its published trace test/example-parallel.in / test/example-parallel.out (commit ff9a3850).
mission parallel {
    output J;
    signal I { par { emit I; } || { await I; emit J; } }
}
