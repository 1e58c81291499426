// Translated from HipHop's test suite: github.com/manuel-serrano/hiphop, test/await-count-pre.strl
// (Esterel v5 source) with its published trace test/await-count-pre.in / test/await-count-pre.out (commit ff9a3850).
mission await3 {
    input I;
    output O;
    loop { await 3 pre(I); emit O; }
}
