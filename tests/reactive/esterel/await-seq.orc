// Translated from HipHop's test suite: github.com/manuel-serrano/hiphop, test/await-seq.strl
// (Esterel v5 source) with its published trace test/await-seq.in / test/await-seq.out (commit ff9a3850).
mission awaitseq {
    input A, B;
    output O;
    await A; await B; emit O;
}
