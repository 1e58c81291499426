// Translated from HipHop's test suite: github.com/manuel-serrano/hiphop, test/trap-nested1.strl
// (Esterel v5 source) with its published trace test/trap-nested1.in / test/trap-nested1.out (commit ff9a3850).
mission trapnested1 {
    output A, B, C, D;
    emit A;
    trap U { trap T { exit T; emit B; } exit U; emit C; }
    emit D;
}
