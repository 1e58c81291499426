// Translated from HipHop's test suite: github.com/manuel-serrano/hiphop, test/reincar2.strl
// (Esterel v5 source) with its published trace test/reincar2.in / test/reincar2.out (commit ff9a3850).
mission reincar2 {
    output S : int, I, J : int;
    loop {
        par { signal M : int := 5 { emit J(?M); pause; emit M(5); } }
        || { signal N { if N { emit I; } pause; emit N; } }
        || { signal L : int { emit L(4); pause; emit S(?L + 5); } }
    }
}
