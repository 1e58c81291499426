// Translated from HipHop's test suite: github.com/manuel-serrano/hiphop, test/trap-par.strl
// (Esterel v5 source) with its published trace test/trap-par.in / test/trap-par.out (commit ff9a3850).
mission trappar {
    output A, B, C;
    trap T { par { emit A; exit T; } || { emit B; pause; emit C; } }
}
