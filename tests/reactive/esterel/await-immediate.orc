// Translated from HipHop's test suite: github.com/manuel-serrano/hiphop, test/await-immediate.strl
// (Esterel v5 source) with its published trace test/await-immediate.in / test/await-immediate.out (commit ff9a3850).
mission awaitimmediate {
    input I;
    output O;
    loop { await immediate I; emit O; pause; }
}
