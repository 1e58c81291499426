// Translated from HipHop's test suite: github.com/manuel-serrano/hiphop, test/trap-par-3.strl
// (Esterel v5 source) with its published trace test/trap-par-3.in / test/trap-par-3.out (commit ff9a3850).
mission trappar3 {
    output S1_and_S2, S1_and_not_S2, not_S1_and_S2, not_S1_and_not_S2;
    signal S1 { signal S2 {
        loop {
            trap T1 {
                par { emit S1; pause; exit T1; }
                || {
                    trap T2 {
                        par { emit S2; pause; exit T2; }
                        || {
                            if S1 {
                                if S2 { emit S1_and_S2; } else { emit S1_and_not_S2; }
                            } else {
                                if S2 { emit not_S1_and_S2; } else { emit not_S1_and_not_S2; }
                            }
                            pause;
                        }
                    }
                }
            }
        }
    } }
}
