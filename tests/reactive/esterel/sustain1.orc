// Translated from HipHop's test suite: github.com/manuel-serrano/hiphop, test/sustain1.strl
// (Esterel v5 source) with its published trace test/sustain1.in / test/sustain1.out (commit ff9a3850).
mission sustain1 {
    input I;
    output J, K;
    loop { abort { sustain J; } when I; emit K; }
}
