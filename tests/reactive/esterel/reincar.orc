// Translated from HipHop's test suite: github.com/manuel-serrano/hiphop, test/reincar.strl
// (Esterel v5 source) with its published trace test/reincar.in / test/reincar.out (commit ff9a3850).
mission reincar {
    output O;
    loop { signal S { if S { emit O; } pause; emit S; } }
}
