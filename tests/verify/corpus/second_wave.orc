// The second-wave constructs under the checker and SPIN: pre as state, relations as
// assumptions (pruned transitions), counted triggers, combine, sub-missions, fail.
input A, B, Go;
relation A # B;

mission Rise {
    output Up;
    loop { if A { if not pre(A) { emit Up; } } pause; }
}
property Rise.holds_up_needs_a: always (Up -> A);
property Rise.holds_up_is_an_edge: always (Up -> not previously A);
property Rise.holds_never_both: never (A and B);
property Rise.fails_up_every_a: always (A -> Up);
property Rise.fails_never_up: never Up;

mission Count {
    output Second, Tot : int combine +;
    par {
        every 2 A { emit Second; }
    } || {
        loop { par { emit Tot(1); } || { emit Tot(2); } pause; }
    }
}
property Count.holds_second_needs_a: always (Second -> A);
property Count.holds_not_first_a: always (Second -> previously once A);
property Count.holds_tot_always: always Tot;
property Count.fails_second_every_a: always (A -> Second);
property Count.fails_never_second: never Second;

mission Wait [input Start; output Ready] { await Start; emit Ready; }

mission Job {
    output R1, R2, Done;
    run mission Wait [Start / Go, Ready / R1];
    run mission Wait [Start / Go, Ready / R2];
    emit Done;
    if pre(R2) { fail Never; }
    halt;
}
property Job.holds_order: always (R2 -> once R1);
property Job.holds_done_with_r2: always (Done <-> R2);
property Job.holds_never_fails: never failed;
property Job.fails_r1_and_r2: eventually (R1 and R2);
property Job.fails_done_first: always (R1 -> Done);

mission Guard {
    input Low;
    output Caught;
    try { loop { await Go; if Low { fail Battery; } } } catch Battery { emit Caught; }
    await Go;
    fail Empty;
}
property Guard.holds_caught_needs_low: always (Caught -> Low);
property Guard.holds_failed_after_caught: always (failed -> once Caught);
property Guard.fails_never_failed: never failed;
property Guard.fails_caught_immediately: always (Low -> Caught);
