// Translated from HipHop's test suite: github.com/manuel-serrano/hiphop, test/example2.strl
// (Esterel v5 source) with its published trace test/example2.in / test/example2.out (commit ff9a3850).
mission example2 {
    output T, V;
    signal S { loop { emit S; if S { emit T; } pause; emit V; } }
}
