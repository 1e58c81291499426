// Translated from HipHop's test suite: github.com/manuel-serrano/hiphop, test/trap-nested2.strl
// (Esterel v5 source) with its published trace test/trap-nested2.in / test/trap-nested2.out (commit ff9a3850).
mission trapnested2 {
    output A, B, C, D;
    emit A;
    trap U { trap T { exit U; emit B; } emit C; }
    emit D;
}
