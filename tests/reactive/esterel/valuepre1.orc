// Translated from HipHop's test suite: github.com/manuel-serrano/hiphop, test/valuepre1.strl
// (Esterel v5 source) with its published trace test/valuepre1.in / test/valuepre1.out (commit ff9a3850).
mission valuepre1 {
    output I : int, O : int := 5 combine +, U : int;
    loop { emit I(3); emit O(?I); emit U(pre(?O)); pause; }
}
