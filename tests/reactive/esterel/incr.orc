// Translated from HipHop's test suite: github.com/manuel-serrano/hiphop, test/incr.strl
// (Esterel v5 source) with its published trace test/incr.in / test/incr.out (commit ff9a3850).
mission Incr {
    input I, R;
    output O : int := 0;
    loop { abort { await I; emit O(pre(?O) + 1); pause; } when R; }
}
