// Translated from HipHop's test suite: github.com/manuel-serrano/hiphop, test/toggle.strl
// (Esterel v5 source) with its published trace test/toggle.in / test/toggle.out (commit ff9a3850).
mission toggle {
    output SEQ : int := 1 combine +, STATE1 : bool := false combine or,
           STATE2 : bool := false combine and, S, TOGGLE : bool;
    loop {
        emit SEQ(pre(?SEQ) + 1);
        emit STATE1(true); emit STATE1(false);
        emit STATE2(true); emit STATE2(false);
        if pre(S) { emit TOGGLE(true); } else { emit TOGGLE(false); emit S; }
        pause;
    }
}
