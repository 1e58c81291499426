/* orccad_rt_automaton.c: the mission's automaton as a task of the real-time controller.
 *
 * A thread of its own (SCHED_FIFO above the processor threads where permitted) reacts at every
 * tick of the mission (ORC_AUTOMATON_TICK_NS, the gcd of the Module-Task periods, released by
 * absolute instants on CLOCK_MONOTONIC from the run's t = 0), and at once when an observer's
 * job fires an event or an input falls due between two ticks, as the executive reacts at an
 * event's instant. A reaction's inputs are the events the observers' jobs fired since the
 * previous one (ORC_AUTOMATON_EVENTS: observer Module-Task -> the automaton input it raises)
 * and the inputs queued by the supervisor (OP_INPUT: the operator's, `--inject`'s), due at
 * their instant; an input already present in the reaction waits for the next one. After a
 * reaction the task applies what it decided, as the mission layer does: the type-1 updates
 * (constant, computed, ramps stepped at the Module-Task's releases: orccad_app/sil/adjust.py)
 * and the Robot-Tasks' lifecycle (starts, kills, activations) of the sites, their run-time
 * arguments bound where the generator found how (plain copies, checked). Each reaction — its request's and its reply's words, orccad_automaton.h — is
 * published through orc_io_reaction (SIL: a ring in the shared memory, from which the
 * supervisor rebuilds the report and applies what is left to it). A negative step (a run-time
 * error of the mission) is published and ends the reactions. C99 + POSIX threads; no
 * allocation. */
#define _POSIX_C_SOURCE 200809L
#include <float.h>
#include <math.h>
#include <string.h>
#include <time.h>

#include "orccad_adjust.h"
#include "orccad_automaton.h"
#include "orccad_io.h"
#include "orccad_rt.h"
#include "orccad_wire.h"

#define MAX_QUEUED 256

static const int input_slots[][2] = ORC_AUTOMATON_INPUT_SLOTS; /* presence word, value words */
static const int event_inputs[][2] = ORC_AUTOMATON_EVENTS;     /* observer, presence word */
static int64_t consumed[ORC_AUTOMATON_N_EVENTS + 1];           /* events already reacted to */
static double queued[MAX_QUEUED][ORC_AUTOMATON_IN_WORDS];      /* word 0: due instant [ns] */
static int n_queued;
static double request[ORC_AUTOMATON_IN_WORDS], reply[ORC_AUTOMATON_OUT_WORDS];
static int started, failed, mission_status;
static int64_t last_clock = -1;

/* The run sites whose lifecycle the task applies: {managed, start output's presence word in
 * the reply (-1: none), first of its Module-Tasks in site_modules, how many, first of its
 * measuring ones, how many, its Robot-Task's number}; a site with run-time arguments is not
 * managed (the supervisor binds them and applies its lifecycle). */
static const int sites[][7] = ORC_AUTOMATON_SITES;
static const int site_modules[] = ORC_AUTOMATON_SITE_MODULES;
static int site_phase[ORC_AUTOMATON_N_SITES + 1];
/* The type-1 updates the task applies (orccad_app/sil/adjust.py): {site, the ADJUST output's
 * presence word in the reply, Module-Task, form (ADJUST_*), first of its parameter words,
 * how many}; a ramp's duration [ns]; a ramp's state: on, its instant [ns since t = 0], ends. */
enum { ADJUST_CONSTANT, ADJUST_COMPUTED, ADJUST_RAMP };
static const int adjusts[][6] = ORC_AUTOMATON_ADJUSTS;
static const int adjust_offsets[] = ORC_AUTOMATON_ADJUST_OFFSETS;
static const double adjust_values[] = ORC_AUTOMATON_ADJUST_VALUES;
static const int64_t adjust_durations[] = ORC_AUTOMATON_ADJUST_DURATIONS;
static struct {
    int on;
    int64_t t0_ns;
    double start, end;
} ramps[ORC_AUTOMATON_N_ADJUSTS + 1];

/* The run-time arguments the task binds at a start (orccad_app/sil/generate/binds.py): {site,
 * the component's word in the reply, Module-Task, parameter word} (a plain copy), and the
 * checks {site, word} of each component: finite, in [low, high]. */
static const int binds[][4] = ORC_AUTOMATON_BINDS;
static const int bind_checks[][2] = ORC_AUTOMATON_BIND_CHECKS;
static const double bind_lows[] = ORC_AUTOMATON_BIND_LOWS;
static const double bind_highs[] = ORC_AUTOMATON_BIND_HIGHS;

/* Site s's run-time arguments in this reaction's reply pass their checks. */
static int arguments_valid(int s)
{
    int i;
    for (i = 0; i < ORC_AUTOMATON_N_BIND_CHECKS; i++) {
        double v = reply[bind_checks[i][1]];
        if (bind_checks[i][0] == s && !(isfinite(v) && v >= bind_lows[i] && v <= bind_highs[i])) {
            return 0;
        }
    }
    return 1;
}

/* Copy site s's run-time arguments into its fresh Module-Tasks' parameter words. */
static void bind_arguments(int s)
{
    int i;
    for (i = 0; i < ORC_AUTOMATON_N_BINDS; i++) {
        if (binds[i][0] == s) {
            (void)orc_rt_set_params(binds[i][2], binds[i][3], &reply[binds[i][1]], 1);
        }
    }
}

/* Update a's computed value (which 0), or its ramp's start (0) and end (1), from the current
 * parameter words; *ok = 0 when the computation refuses. */
static double adjust_value(int a, int which, int *ok)
{
    (void)ok;
    switch (2 * a + which) {
    ORC_AUTOMATON_ADJUST_VALUE_CASES
    default:
        break;
    }
    return 0.0;
}

/* v is a value update a's parameter takes (its declared range, finite). */
static int adjust_valid(int a, double v)
{
    (void)v;
    switch (a) {
    ORC_AUTOMATON_ADJUST_CHECK_CASES
    default:
        break;
    }
    return 1;
}

void orc_automaton_start(void)
{
    started = 1;
}

uint32_t orc_automaton_input(const double *words, uint32_t n)
{
    if (n != ORC_AUTOMATON_IN_WORDS) {
        return ORC_BAD_WORDS;
    }
    if (n_queued == MAX_QUEUED) {
        return ORC_INPUTS_FULL; /* more inputs ahead than a reaction period can hold */
    }
    memcpy(queued[n_queued++], words, n * sizeof(double));
    return ORC_OK;
}

static int event_pending(void)
{
    int i;
    for (i = 0; i < ORC_AUTOMATON_N_EVENTS; i++) {
        if (orc_rt_events(event_inputs[i][0]) > consumed[i]) {
            return 1;
        }
    }
    return 0;
}

/* The queued inputs due at `clock` merged into the request, in their order, until one meets
 * an input already present (it waits for the next reaction). */
static void take_inputs(int64_t clock)
{
    int q = 0, i;
    for (; q < n_queued && orc_word_int(&queued[q][0]) <= clock; q++) {
        int meets = 0;
        for (i = 0; i < ORC_AUTOMATON_N_INPUTS; i++) {
            int at = input_slots[i][0];
            meets |= orc_word_int(&queued[q][at]) != 0 && orc_word_int(&request[at]) != 0;
        }
        if (meets) {
            break;
        }
        for (i = 0; i < ORC_AUTOMATON_N_INPUTS; i++) {
            int at = input_slots[i][0];
            if (orc_word_int(&queued[q][at]) != 0) {
                memcpy(&request[at], &queued[q][at], (size_t)(1 + input_slots[i][1]) * sizeof(double));
            }
        }
    }
    if (q > 0) {
        memmove(queued[0], queued[q], (size_t)(n_queued - q) * sizeof queued[0]);
        n_queued -= q;
    }
}

static int wanted(int s, int phase, int m)
{
    int i, first = phase >= 3 ? sites[s][2] : sites[s][4];
    int count = phase >= 3 ? sites[s][3] : phase == 2 ? sites[s][5] : 0;
    for (i = first; i < first + count; i++) {
        if (site_modules[i] == m) {
            return 1;
        }
    }
    return 0;
}

/* Site s is the first running site of its Robot-Task (the one a type-1 update applies to,
 * as the mission layer finds it: the phases before the reaction's lifecycle). */
static int first_running(int s)
{
    int other;
    if (site_phase[s] == 0) {
        return 0;
    }
    for (other = 0; other < s; other++) {
        if (sites[other][6] == sites[s][6] && site_phase[other] > 0) {
            return 0;
        }
    }
    return 1;
}

static void write_param(int a, double value)
{
    int i;
    for (i = adjusts[a][4]; i < adjusts[a][4] + adjusts[a][5]; i++) {
        orc_rt_set_param(adjusts[a][2], adjust_offsets[i], value);
    }
}

/* The ramps on update a's parameter stop (a new update of it, or its task's run ended). */
static void stop_ramps(int module, int offset)
{
    int r;
    for (r = 0; r < ORC_AUTOMATON_N_ADJUSTS; r++) {
        if (ramps[r].on && adjusts[r][2] == module
            && (offset < 0 || adjust_offsets[adjusts[r][4]] == offset)) {
            ramps[r].on = 0;
        }
    }
}

/* Update a applied in the reaction at `clock` [ns since t = 0], as the mission layer applies
 * it (TypeOneUpdates.apply): a constant's words; a computed value, checked; a ramp's ends
 * computed and checked, its start written at once, its steps at the releases to come. A
 * value refused is not written (the supervisor ends the run with the reason). */
static void apply_update(int a, int64_t clock)
{
    int i, ok = 1, form = adjusts[a][3];
    double value, end = 0.0;
    if (adjusts[a][5] > 0) {
        stop_ramps(adjusts[a][2], adjust_offsets[adjusts[a][4]]);
    }
    if (form == ADJUST_CONSTANT) {
        for (i = adjusts[a][4]; i < adjusts[a][4] + adjusts[a][5]; i++) {
            orc_rt_set_param(adjusts[a][2], adjust_offsets[i], adjust_values[i]);
        }
        return;
    }
    value = adjust_value(a, 0, &ok);
    if (form == ADJUST_RAMP) {
        end = adjust_value(a, 1, &ok);
        ok = ok && adjust_valid(a, end);
    }
    if (!ok || !adjust_valid(a, value)) {
        return;
    }
    write_param(a, value);
    if (form == ADJUST_RAMP) {
        ramps[a].on = 1;
        ramps[a].t0_ns = clock;
        ramps[a].start = value;
        ramps[a].end = end;
    }
}

/* The type-1 updates the reaction emitted, in output order, applied to their Module-Task's
 * parameters (between two of its jobs). */
static void adjust(int64_t clock)
{
    int a;
    for (a = 0; a < ORC_AUTOMATON_N_ADJUSTS; a++) {
        if (orc_word_int(&reply[adjusts[a][1]]) != 0 && first_running(adjusts[a][0])) {
            apply_update(a, clock);
        }
    }
}

void orc_automaton_release(int m, int64_t release_ns)
{
    int a;
    for (a = 0; a < ORC_AUTOMATON_N_ADJUSTS; a++) {
        int64_t since = release_ns - ramps[a].t0_ns, duration = adjust_durations[a];
        double fraction, value;
        if (!ramps[a].on || adjusts[a][2] != m || since <= 0) {
            continue;
        }
        if (ORC_MODULES[m].sporadic && since < duration && ORC_MODULES[m].period_ns > 0) {
            /* the executive steps a sporadic Module-Task's ramp every minimum inter-arrival
             * from the update: this job sees the last step before its release */
            since = since / ORC_MODULES[m].period_ns * ORC_MODULES[m].period_ns;
            if (since <= 0) {
                continue; /* the start, written with the update */
            }
        }
        /* the executive's step: min(1, dt / D), both exact as doubles */
        fraction = since >= duration ? 1.0 : (double)since / (double)duration;
        value = ramps[a].start + (ramps[a].end - ramps[a].start) * fraction;
        ramps[a].on = since < duration;
        if (adjust_valid(a, value)) {
            write_param(a, value);
        }
    }
}

/* The Robot-Tasks' lifecycle the reaction decided, as the mission layer applies it
 * (MissionRun._update_sites): a start or restart loads fresh Module-Tasks and fresh ports,
 * the Module-Tasks its new phase does not want are killed, those it wants activated, their
 * first release shared at `release_ns`. */
static void lifecycle(int64_t release_ns)
{
    int s, i;
    for (s = 0; s < ORC_AUTOMATON_N_SITES; s++) {
        int old = site_phase[s], phase = orc_automaton_phase(s), start = sites[s][1];
        int restart = old > 0 && phase > 0 && start >= 0 && orc_word_int(&reply[start]) != 0;
        int starting = phase > 0 && (old == 0 || restart);
        int first = sites[s][2], count = sites[s][3];
        site_phase[s] = phase;
        for (i = first; old > 0 && (phase == 0 || restart) && i < first + count; i++) {
            stop_ramps(site_modules[i], -1); /* the run ended: its ramps stop */
        }
        if (!sites[s][0]) {
            continue;
        }
        if (starting && !arguments_valid(s)) { /* refused: the mission fails, as in the */
            failed = 1;                        /* mission layer (the supervisor says why) */
            return;
        }
        for (i = first; i < first + count; i++) {
            int m = site_modules[i];
            if (orc_rt_active(m) && (restart || !wanted(s, phase, m))) {
                orc_rt_kill(m);
            }
        }
        for (i = first; starting && i < first + count; i++) {
            orc_rt_fresh(site_modules[i]);
            orc_rt_reset_ports(site_modules[i]);
        }
        if (starting) {
            bind_arguments(s);
        }
        for (i = first; i < first + count; i++) {
            int m = site_modules[i];
            if (wanted(s, phase, m) && !orc_rt_active(m)) {
                orc_rt_activate(m, release_ns);
            }
        }
    }
}

/* One reaction at `clock` [ns since t = 0]. */
static void react(int64_t clock)
{
    int i;
    uint32_t n = 0;
    memset(request, 0, sizeof request);
    orc_word_set_int(&request[0], clock);
    for (i = 0; i < ORC_AUTOMATON_N_EVENTS; i++) {
        int64_t events = orc_rt_events(event_inputs[i][0]);
        if (events > consumed[i]) {
            consumed[i] = events;
            orc_word_set_int(&request[event_inputs[i][1]], 1);
        }
    }
    take_inputs(clock);
    if (orc_automaton_react(request, ORC_AUTOMATON_IN_WORDS, reply, &n) != 0) {
        failed = 1;
        return;
    }
    last_clock = clock;
    failed = orc_word_int(&reply[0]) < 0;
    mission_status = failed ? -1 : (int)orc_word_int(&reply[0]);
    if (!failed) {
        int64_t at = orc_rt_epoch_ns() + clock, now = orc_rt_now_ns();
        adjust(clock);
        lifecycle(at > now ? at : now);
        if (failed) {
            mission_status = -1;
        }
    }
    orc_io_reaction(request, ORC_AUTOMATON_IN_WORDS, reply, n);
}

int orc_automaton_status(void)
{
    return failed && mission_status >= 0 ? -1 : mission_status;
}

void *orc_automaton_task(void *unused)
{
    int64_t tick = 0;
    (void)unused;
    pthread_mutex_lock(&orc_rt_lock);
    while (!orc_rt_stopping) {
        int64_t epoch = orc_rt_epoch_ns(), next = orc_rt_now_ns() + 1000000;
        struct timespec ts;
        if (started && !failed) {
            int64_t since = orc_rt_now_ns() - epoch;
            while (!failed && tick * ORC_AUTOMATON_TICK_NS <= since) { /* every tick due: */
                react(tick * ORC_AUTOMATON_TICK_NS);                  /* the timers count them */
                tick += 1;
            }
            if (!failed && (event_pending()
                            || (n_queued > 0 && orc_word_int(&queued[0][0]) <= since))) {
                react(since > last_clock ? since : last_clock); /* an event's instant */
            }
            next = epoch + tick * ORC_AUTOMATON_TICK_NS;
        }
        ts.tv_sec = (time_t)(next / 1000000000LL);
        ts.tv_nsec = (long)(next % 1000000000LL);
        pthread_cond_timedwait(&orc_rt_changed, &orc_rt_lock, &ts); /* a tick, or an event */
    }
    pthread_mutex_unlock(&orc_rt_lock);
    return NULL;
}
