// Translated from HipHop's test suite: github.com/manuel-serrano/hiphop, test/example1.strl
// (Esterel v5 source) with its published trace test/example1.in / test/example1.out (commit ff9a3850).
mission example1 {
    output T;
    signal S { pause; emit S; if S { emit T; } }
}
