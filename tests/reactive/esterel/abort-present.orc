// Translated from HipHop's test suite: github.com/manuel-serrano/hiphop, test/abort-present.strl
// (Esterel v5 source) with its published trace test/abort-present.in / test/abort-present.out (commit ff9a3850).
mission abortpresent {
    input I;
    output J, V, K;
    loop {
        abort { emit J; pause; emit V; pause; } when I;
        if I { emit K; }
    }
}
