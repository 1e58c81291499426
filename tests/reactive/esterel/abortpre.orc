// Translated from HipHop's test suite: github.com/manuel-serrano/hiphop, test/abortpre.strl
// (Esterel v5 source) with its published trace test/abortpre.in / test/abortpre.out (commit ff9a3850).
mission abortpre {
    output O, S;
    loop { abort { emit S; pause; emit O; } when pre(S); pause; }
}
