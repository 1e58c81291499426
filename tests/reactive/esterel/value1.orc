// Translated from HipHop's test suite: github.com/manuel-serrano/hiphop, test/value1.strl
// (Esterel v5 source) with its published trace test/value1.in / test/value1.out (commit ff9a3850).
mission value1 {
    output O : int := 5 combine +;
    loop { emit O(5); emit O(10); pause; }
}
