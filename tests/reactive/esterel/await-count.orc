// Translated from HipHop's test suite: github.com/manuel-serrano/hiphop, test/await-count.strl
// (Esterel v5 source) with its published trace test/await-count.in / test/await-count.out (commit ff9a3850).
mission await3 {
    input I;
    output O;
    loop { await 3 I; emit O; }
}
