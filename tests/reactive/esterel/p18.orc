// Translated from HipHop's test suite: github.com/manuel-serrano/hiphop, test/p18.strl
// (Esterel v5 source) with its published trace test/p18.in / test/p18.out (commit ff9a3850).
mission P18 {
    output S1_and_S2, S1_and_not_S2, not_S1_and_S2, not_S1_and_not_S2;
    loop {
        trap T1 {
            signal S1 {
                par { pause; emit S1; exit T1; }
                || {
                    loop {
                        trap T2 {
                            signal S2 {
                                par { pause; emit S2; exit T2; }
                                || {
                                    loop {
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
                }
            }
        }
    }
}
