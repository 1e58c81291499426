// Translated from HipHop's test suite: github.com/manuel-serrano/hiphop, test/suspend.strl
// (Esterel v5 source) with its published trace test/suspend.in / test/suspend.out (commit ff9a3850).
mission SUSPEND {
    input I;
    output O, J;
    suspend { sustain O; } when I;
    emit J;
}
