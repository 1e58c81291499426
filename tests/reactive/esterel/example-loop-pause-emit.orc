// Translated from HipHop's test suite: github.com/manuel-serrano/hiphop, test/example-loop-pause-emit.strl
// (Esterel v5 source) with its published trace test/example-loop-pause-emit.in / test/example-loop-pause-emit.out (commit ff9a3850).
mission looppauseemit {
    input I;
    output S;
    loop { await I; pause; emit S; }
}
