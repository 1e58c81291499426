// Translated from HipHop's test suite: github.com/manuel-serrano/hiphop, test/emitvaluedlocal2.strl
// (Esterel v5 source) with its published trace test/emitvaluedlocal2.in / test/emitvaluedlocal2.out (commit ff9a3850).
mission emitvaluedlocal2 {
    output O : int;
    loop {
        signal S : int := 1 combine + { emit S(pre(?S) + 1); emit O(?S); }
        pause;
    }
}
