// Translated from HipHop's test suite: github.com/manuel-serrano/hiphop, test/cross-await.strl
// (Esterel v5 source) with its published trace test/cross-await.in / test/cross-await.out (commit ff9a3850).
mission crossawait {
    output A, B, END1, END2;
    par { emit A; await immediate B; emit END1; }
    || { emit B; await immediate A; emit END2; }
}
