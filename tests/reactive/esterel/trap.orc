// Translated from HipHop's test suite: github.com/manuel-serrano/hiphop, test/trap.strl
// (Esterel v5 source) with its published trace test/trap.in / test/trap.out (commit ff9a3850).
mission trapsimple {
    output A, B, C;
    emit A;
    trap T { exit T; emit B; }
    emit C;
}
