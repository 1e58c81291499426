// Translated from HipHop's test suite: github.com/manuel-serrano/hiphop, test/abort-par.strl
// (Esterel v5 source) with its published trace test/abort-par.in / test/abort-par.out (commit ff9a3850).
mission abortpar {
    input I;
    output O;
    signal L {
        par { abort { loop { emit O; pause; } } when L; }
        || { await I; emit L; }
    }
}
