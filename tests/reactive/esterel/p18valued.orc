// Translated from HipHop's test suite: github.com/manuel-serrano/hiphop, test/p18valued.strl
// (Esterel v5 source) with its published trace test/p18valued.in / test/p18valued.out (commit ff9a3850).
mission P18valued {
    output S1_and_S2 : int, S1_and_not_S2 : int, not_S1_and_S2 : int, not_S1_and_not_S2 : int;
    loop {
        trap T1 {
            signal S1 : int := 10 combine + {
                par { pause; emit S1(pre(?S1)); exit T1; }
                || {
                    loop {
                        trap T2 {
                            signal S2 : int := 20 combine + {
                                par { pause; emit S2(pre(?S2)); exit T2; }
                                || {
                                    loop {
                                        if S1 {
                                            if S2 { emit S1_and_S2(?S1 + ?S2); }
                                            else { emit S1_and_not_S2(?S1 + ?S2); }
                                        } else {
                                            if S2 { emit not_S1_and_S2(?S1 + ?S2); }
                                            else { emit not_S1_and_not_S2(?S1 + ?S2); }
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
