// Translated from HipHop's test suite: github.com/manuel-serrano/hiphop, test/await-par.strl
// (Esterel v5 source) with its published trace test/await-par.in / test/await-par.out (commit ff9a3850).
mission awaitpar {
    input A, B;
    output O;
    par { await A; } || { await B; }
    emit O;
}
