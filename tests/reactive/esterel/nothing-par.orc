// Translated from HipHop's test suite: github.com/manuel-serrano/hiphop, test/nothing-par.strl
// (Esterel v5 source) with its published trace test/nothing-par.in / test/nothing-par.out (commit ff9a3850).
mission nothingpar {
    par { nothing; pause; } || { nothing; }
}
