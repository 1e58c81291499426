// Translated from HipHop's test suite: github.com/manuel-serrano/hiphop, test/emitvaluedlocal1.strl
// (Esterel v5 source) with its published trace test/emitvaluedlocal1.in / test/emitvaluedlocal1.out (commit ff9a3850).
mission emitvaluedlocal1 {
    output O : int;
    loop {
        signal S : int := 1 combine + { emit S(pre(?S) + 1); emit O(?S); }
        pause;
        emit O(pre(?O));
        pause;
    }
}
