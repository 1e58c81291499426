/* orccad_rt.c: the real-time controller of `orccad sil --realtime`.
 *
 * One thread per processor of the placement runs the active Module-Tasks placed on it:
 * periodic releases by clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME), jobs in priority
 * order (1 the highest) at each release instant, read -> compute -> write. A sporadic
 * Module-Task is released by the writes on its inputs, at least its minimum inter-arrival
 * apart (deferred, coalesced); another thread's write wakes its thread at once. The threads run
 * under SCHED_FIFO when the system permits it (priority 80 minus the processor's highest
 * Module-Task priority), else under the default policy after a warning on stderr.
 *
 * Ports: each connection between Module-Tasks runs its protocol (orccad_port.h: the 8 of
 * RR-1801, as the executive runs them on one processor). A job reads its inputs in port order
 * at its release (the jobs released together read in priority order before any computes), is
 * computed in priority order, then writes its outputs in port order; a read or write that its protocol blocks
 * leaves the job waiting there while the thread runs its processor's other jobs, and the
 * other end's operation (on any thread) releases it. A thread with a blocked job or an active
 * sporadic Module-Task waits on the runtime's condition variable (CLOCK_MONOTONIC, absolute)
 * rather than in clock_nanosleep, so that another thread's write wakes it at once. Robot ports go through the I/O functions
 * of orccad_io.h: over the plant server's shared memory in SIL (orccad_io_shm.c), the
 * hardware's on a robot. Each job's measured timing (release lateness, overruns, deadline
 * misses, response time) and outputs are published through them too, and, while the I/O side
 * wants them (a trace), each job's life cycle and each skipped release (orc_io_job).
 *
 * The mission's automaton is a task of its own (orccad_rt_automaton.c: it reacts at its
 * ticks and at the observers' events, and publishes each reaction through orc_io_reaction).
 * The plant server applies the Robot-Tasks' lifecycle the automaton decides over the socket
 * (orccad_rt_main.c, file descriptor argv[2]): START (fresh Module-Task, nominal parameters), PARAM (a type-1
 * update), INIT, ACTIVATE (first release at a given instant), KILL, RESET (its ports' values
 * dropped), INPUT (an input for the automaton at an instant), EPOCH (t = 0: the automaton
 * starts), PING (the heartbeat) and QUIT, with the frames of orccad_lockstep.c. Commands, the
 * automaton's reactions and the jobs' port operations take one runtime lock; a job's compute
 * runs outside it (the jobs of different processors overlap in time), and a command touching
 * a Module-Task's memory waits for its compute to end. The commands' thread runs under
 * SCHED_FIFO too (priority 70) when the processor
 * threads do: a supervisor waiting for an answer holds the plant.
 *
 * This file holds the Module-Tasks' state (orccad_rt_task.h), the port wiring, the jobs' state
 * machine and the processor threads; the Robot-Tasks' lifecycle on a Module-Task is
 * orccad_rt_lifecycle.c, the trace's job records orccad_rt_record.c, the deadlock search (a
 * cycle of jobs blocked on each other's ports) orccad_rt_deadlock.c.
 *
 * C99 + POSIX threads; no allocation after start, no recursion. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <pthread.h>
#include <sched.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "orccad_io.h"
#include "orccad_mt.h"
#include "orccad_port.h"
#include "orccad_rt.h"
#include "orccad_rt_task.h"

#define MAX_MODULES ORC_RT_MAX_MODULES
#define MAX_CONNECTIONS 256
#define MAX_PROCESSORS ORC_RT_MAX_PROCESSORS

pthread_mutex_t orc_rt_lock = PTHREAD_MUTEX_INITIALIZER;
pthread_cond_t orc_rt_changed; /* a port, an interrupt or a command changed (monotonic) */
static rt_task tasks[MAX_MODULES];
static orc_port ports[MAX_CONNECTIONS];
static int input_of[MAX_MODULES][ORC_MAX_PORTS]; /* the connection into each input slot */
static int writes[MAX_CONNECTIONS];              /* connections by producer, in port order */
static int first_write[MAX_MODULES + 1];
volatile int orc_rt_stopping;
static int64_t epoch_ns;

static int64_t now_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (int64_t)ts.tv_sec * 1000000000LL + ts.tv_nsec;
}

int64_t orc_rt_now_ns(void)
{
    return now_ns();
}

int64_t orc_rt_epoch_ns(void)
{
    return epoch_ns;
}

int64_t orc_rt_events(int m)
{
    return tasks[m].events;
}

rt_task *orc_rt_task(int m)
{
    return &tasks[m];
}

orc_port *orc_rt_port(int c)
{
    return &ports[c];
}

static struct timespec timespec_of(int64_t ns)
{
    struct timespec ts;
    ts.tv_sec = (time_t)(ns / 1000000000LL);
    ts.tv_nsec = (long)(ns % 1000000000LL);
    return ts;
}

/* The wiring's indexes: each input slot's connection (-1: none), and each Module-Task's
 * writes in the order of its output slots (as the executive writes them). */
static void index_wiring(void)
{
    int m, s, c, n = 0;
    for (m = 0; m < ORC_N_MODULES; m++) {
        for (s = 0; s < ORC_MAX_PORTS; s++) {
            input_of[m][s] = -1;
        }
    }
    for (c = 0; c < ORC_N_CONNECTIONS; c++) {
        const orc_connection *k = &ORC_CONNECTIONS[c];
        orc_port_reset(&ports[c], k->protocol);
        if (k->dst_module >= 0) {
            input_of[k->dst_module][k->dst_slot] = c;
        }
    }
    for (m = 0; m < ORC_N_MODULES; m++) {
        first_write[m] = n;
        for (s = 0; s < ORC_MAX_PORTS; s++) {
            for (c = 0; c < ORC_N_CONNECTIONS; c++) {
                if (ORC_CONNECTIONS[c].src_module == m && ORC_CONNECTIONS[c].src_slot == s) {
                    writes[n++] = c;
                }
            }
        }
    }
    first_write[ORC_N_MODULES] = n;
}

/* ---- one job: read (a protocol may block it), compute, write (may block) ---------------- */

/* A read's value into an input slot (its dimension is the slot's own). */
static void take(orc_value *slot, const orc_value *value)
{
    slot->present = value->present;
    memcpy(slot->v, value->v, sizeof slot->v);
}

/* A write on an input of sporadic Module-Task m: released now, or deferred to its minimum
 * inter-arrival after the previous release; coalesced into a release already due; ignored
 * while m is inactive (executive/sporadic.py's semantics). */
static void interrupt(int m)
{
    rt_task *t = &tasks[m];
    int64_t now = now_ns(), earliest;
    if (!t->active || t->next_release_ns != INT64_MAX) {
        return;
    }
    earliest = t->last_release_ns == INT64_MIN ? now
                                              : t->last_release_ns + ORC_MODULES[m].period_ns;
    t->next_release_ns = earliest > now ? earliest : now;
}


/* Reads the inputs from t->at on; 0 when blocked on one. */
static int read_inputs(int m)
{
    rt_task *t = &tasks[m];
    orc_mt *mt = &ORC_INSTANCES[m];
    orc_value value;
    for (; t->at < mt->n_in; t->at++) {
        int c = input_of[m][t->at];
        orc_value *slot = &mt->in[t->at];
        if (c < 0) {
            slot->present = 0;
        } else if (ORC_CONNECTIONS[c].src_module < 0) {
            orc_io_read_sensor(ORC_CONNECTIONS[c].src_slot, slot);
        } else {
            int done = t->waiting ? orc_port_read_done(&ports[c], &value)
                                  : orc_port_read(&ports[c], &value);
            t->waiting = done == ORC_PORT_BLOCKED;
            if (t->waiting) {
                return 0;
            }
            take(slot, &value);
        }
    }
    return 1;
}

/* Writes the outputs from t->at on; 0 when blocked on one. */
static int write_outputs(int m)
{
    rt_task *t = &tasks[m];
    orc_mt *mt = &ORC_INSTANCES[m];
    for (; first_write[m] + t->at < first_write[m + 1]; t->at++) {
        int c = writes[first_write[m] + t->at];
        const orc_connection *k = &ORC_CONNECTIONS[c];
        const orc_value *out = &mt->out[k->src_slot];
        if (!t->waiting && !out->present) {
            continue;
        }
        if (k->dst_module < 0) {
            orc_io_write_actuator(k->dst_slot, out);
            continue;
        }
        if (!t->waiting && ORC_MODULES[k->dst_module].sporadic) {
            interrupt(k->dst_module);
        }
        t->waiting = (t->waiting ? orc_port_write_done(&ports[c]) : orc_port_write(&ports[c], out))
                     == ORC_PORT_BLOCKED;
        if (t->waiting) {
            return 0;
        }
    }
    return 1;
}

int orc_rt_job_connection(int m)
{
    const rt_task *t = &tasks[m];
    return t->phase == JOB_READING ? input_of[m][t->at] : writes[first_write[m] + t->at];
}

static void finish_job(int m)
{
    rt_task *t = &tasks[m];
    int64_t now = now_ns();
    double response = (double)(now - t->job_release_ns);
    int missed = response > (double)ORC_MODULES[m].period_ns;
    if (ORC_MODULES[m].event_out && ORC_INSTANCES[m].out[0].present) {
        t->events += 1; /* an observer's event (slot 0): counted for the plant server */
    }
    t->phase = JOB_IDLE;
    if (response > t->response_max_ns) {
        t->response_max_ns = response;
    }
    if (missed) {
        t->misses += 1;
    }
    if (t->job_traced) {
        orc_rt_record_job(m, now, missed);
    }
    orc_io_publish(m, &ORC_INSTANCES[m], t->released, t->overruns, t->misses, t->events,
                   t->response_max_ns);
}

/* Takes the job of m as far as its ports let it; 1 when it moved. */
static int advance(int m)
{
    rt_task *t = &tasks[m];
    int at = t->at, phase = t->phase;
    if (t->phase == JOB_READING && read_inputs(m)) {
        /* The compute runs outside the lock (it touches only the Module-Task's own memory,
         * which a command waits for): the jobs of different processors overlap in time. */
        unsigned generation = t->generation;
        double t_s = (double)(t->job_release_ns - epoch_ns) * 1e-9;
        int64_t compute_end = -1;
        int traced = t->job_traced;
        t->computing = 1;
        if (traced) {
            t->job_start_ns = now_ns();
        }
        pthread_mutex_unlock(&orc_rt_lock);
        orc_mt_compute(&ORC_INSTANCES[m], t_s);
        if (traced) {
            compute_end = now_ns(); /* before the lock: its wait is the write's, not compute */
        }
        pthread_mutex_lock(&orc_rt_lock);
        t->computing = 0;
        t->job_compute_end_ns = compute_end;
        pthread_cond_broadcast(&orc_rt_changed); /* a command may wait for it */
        if (t->generation != generation) {
            return 1; /* killed or activated anew meanwhile: the job is aborted */
        }
        t->phase = JOB_WRITING;
        t->at = 0;
    }
    if (t->phase == JOB_WRITING && write_outputs(m)) {
        finish_job(m);
    }
    return t->phase != phase || t->at != at;
}

/* The releases due at `now` on `processor`: a job starts (reading), or the release is skipped
 * and counted as an overrun while the previous job is unfinished. */
static void release_due(int processor, int64_t now, int *released)
{
    int m;
    for (m = 0; m < ORC_N_MODULES; m++) {
        rt_task *t = &tasks[m];
        int64_t period = ORC_MODULES[m].period_ns, release = t->next_release_ns;
        if (!t->active || ORC_MODULES[m].processor != processor || release > now) {
            continue;
        }
        if (t->phase != JOB_IDLE) {
            t->overruns += 1;
            orc_rt_record_overrun(m, release);
        } else {
            t->phase = JOB_READING;
            t->at = 0;
            t->waiting = 0;
            t->job_release_ns = release;
            t->job_start_ns = t->job_compute_end_ns = -1;
            t->job_traced = orc_io_jobs_wanted();
            t->released += 1;
            released[m] = 1;
            orc_io_lateness(m, (double)(now - release));
            orc_automaton_release(m, release - epoch_ns);
        }
        if (ORC_MODULES[m].sporadic) { /* the next release comes from an interrupt */
            t->last_release_ns = release;
            t->next_release_ns = INT64_MAX;
            continue;
        }
        t->next_release_ns = release + period;
        while (t->next_release_ns <= now) { /* releases missed: overruns */
            t->overruns += 1;
            orc_rt_record_overrun(m, t->next_release_ns);
            t->next_release_ns += period;
        }
    }
}

/* The jobs just released on `processor` read their inputs at once, in priority order, as
 * the executive's jobs read at their release (before any of them computes). */
static void read_at_release(int processor, const int *released)
{
    int priority, m;
    for (priority = 1; priority <= 99; priority++) {
        for (m = 0; m < ORC_N_MODULES; m++) {
            if (released[m] && ORC_MODULES[m].processor == processor
                && ORC_MODULES[m].priority == priority) {
                (void)read_inputs(m);
            }
        }
    }
}

/* The jobs of `processor` in priority order (1 the highest), each as far as it goes; after
 * a job moves, from the highest again (it may have released one blocked on its port). */
static int run_jobs(int processor)
{
    int moved_any = 0, moved = 1;
    while (moved && !orc_rt_stopping) {
        int priority, m;
        moved = 0;
        for (priority = 1; priority <= 99 && !moved; priority++) {
            for (m = 0; m < ORC_N_MODULES && !moved; m++) {
                if (tasks[m].active && tasks[m].phase != JOB_IDLE
                    && ORC_MODULES[m].processor == processor
                    && ORC_MODULES[m].priority == priority) {
                    moved = advance(m);
                }
            }
        }
        moved_any |= moved;
    }
    return moved_any;
}

/* ---- processor threads ------------------------------------------------------------------- */

static void *processor_thread(void *arg)
{
    int processor = (int)(intptr_t)arg;
    pthread_mutex_lock(&orc_rt_lock);
    while (!orc_rt_stopping) {
        int64_t next = INT64_MAX;
        int m, waits = 0, released[MAX_MODULES] = {0};
        struct timespec ts;
        release_due(processor, now_ns(), released);
        read_at_release(processor, released);
        if (run_jobs(processor)) {
            pthread_cond_broadcast(&orc_rt_changed); /* a port moved: other threads look again */
        }
        for (m = 0; m < ORC_N_MODULES; m++) {
            if (!tasks[m].active || ORC_MODULES[m].processor != processor) {
                continue;
            }
            if (tasks[m].next_release_ns < next) {
                next = tasks[m].next_release_ns;
            }
            waits |= tasks[m].phase != JOB_IDLE || ORC_MODULES[m].sporadic;
        }
        if (next == INT64_MAX) { /* nothing due here: look again in 200 µs */
            next = now_ns() + 200000;
        }
        ts = timespec_of(next);
        if (waits) { /* a blocked job or an interrupt: another thread may signal it */
            pthread_cond_timedwait(&orc_rt_changed, &orc_rt_lock, &ts);
            continue;
        }
        pthread_mutex_unlock(&orc_rt_lock);
        while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, NULL) == EINTR) {
        }
        pthread_mutex_lock(&orc_rt_lock);
    }
    pthread_mutex_unlock(&orc_rt_lock);
    return NULL;
}

int orc_rt_start_thread(pthread_t *thread, void *(*body)(void *), void *arg, int priority,
                        int *warned)
{
    pthread_attr_t attr;
    struct sched_param param;
    int error;
    pthread_attr_init(&attr);
    pthread_attr_setinheritsched(&attr, PTHREAD_EXPLICIT_SCHED);
    pthread_attr_setschedpolicy(&attr, SCHED_FIFO);
    param.sched_priority = priority;
    pthread_attr_setschedparam(&attr, &param);
    if (getenv("ORCCAD_NO_FIFO") != NULL) {
        error = EPERM;
    } else {
        error = pthread_create(thread, &attr, body, arg);
    }
    pthread_attr_destroy(&attr);
    if (error == EPERM) {
        if (!*warned) {
            fprintf(stderr, "orccad: warning: SCHED_FIFO is not permitted here (%s); the "
                            "processor threads run under the default policy\n",
                    getenv("ORCCAD_NO_FIFO") != NULL ? "ORCCAD_NO_FIFO is set"
                                                     : "no CAP_SYS_NICE or RLIMIT_RTPRIO");
            *warned = 1;
        }
        error = pthread_create(thread, NULL, body, arg);
    }
    return error;
}

/* The thread of `processor`: priority 80 minus its best Module-Task priority (1 the highest). */
static int start_processor(pthread_t *thread, int processor, int *warned)
{
    int m, best = 99;
    for (m = 0; m < ORC_N_MODULES; m++) {
        if (ORC_MODULES[m].processor == processor && ORC_MODULES[m].priority < best) {
            best = ORC_MODULES[m].priority;
        }
    }
    return orc_rt_start_thread(thread, processor_thread, (void *)(intptr_t)processor,
                               best < 79 ? 80 - best : 1, warned);
}

/* ---- set up and stop --------------------------------------------------------------------- */

void orc_rt_take_epoch(void)
{
    epoch_ns = orc_io_epoch_ns(epoch_ns);
}

int orc_rt_setup(void)
{
    pthread_condattr_t condattr;
    if (ORC_N_MODULES > MAX_MODULES || ORC_N_CONNECTIONS > MAX_CONNECTIONS
        || ORC_N_PROCESSORS > MAX_PROCESSORS) {
        return -1;
    }
    epoch_ns = now_ns();
    index_wiring();
    pthread_condattr_init(&condattr);
    pthread_condattr_setclock(&condattr, CLOCK_MONOTONIC);
    pthread_cond_init(&orc_rt_changed, &condattr);
    pthread_condattr_destroy(&condattr);
    return 0;
}

int orc_rt_start_processor(pthread_t *thread, int processor, int *warned)
{
    return start_processor(thread, processor, warned);
}

void orc_rt_stop(void)
{
    pthread_mutex_lock(&orc_rt_lock);
    orc_rt_stopping = 1;
    pthread_cond_broadcast(&orc_rt_changed);
    pthread_mutex_unlock(&orc_rt_lock);
}
