// Translated from HipHop's test suite: github.com/manuel-serrano/hiphop, test/example3.strl
// (Esterel v5 source) with its published trace test/example3.in / test/example3.out (commit ff9a3850).
mission example3 {
    input A;
    output T, V;
    signal S { abort { loop { emit S; if S { emit T; } pause; emit V; } } when A; }
}
