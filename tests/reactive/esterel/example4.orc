// Translated from HipHop's test suite: github.com/manuel-serrano/hiphop, test/example4.strl
// (Esterel v5 source) with its published trace test/example4.in / test/example4.out (commit ff9a3850).
mission example4 {
    input A;
    output T, V;
    signal S { loop { abort { emit S; if S { emit T; } pause; emit V; } when A; } }
}
