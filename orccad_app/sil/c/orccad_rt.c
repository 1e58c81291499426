/* orccad_rt.c: the real-time controller of `orccad sil --realtime`.
 *
 * One thread per processor of the placement runs the active Module-Tasks placed on it:
 * periodic releases by clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME), jobs in priority
 * order (1 the highest) at each release instant, read -> compute -> write. A sporadic
 * Module-Task is released by the writes on its inputs, at least its minimum inter-arrival
 * apart (deferred, coalesced); a thread with an active sporadic one wakes every 100 µs at
 * least to see an interrupt from another thread. The threads run
 * under SCHED_FIFO when the system permits it (priority 80 minus the processor's highest
 * Module-Task priority), else under the default policy after a warning on stderr.
 *
 * Ports: connections between Module-Tasks are asyn/asyn buffers (the last value; "none yet"
 * before the first write, and again after a reset). Robot ports go through the I/O functions
 * of orccad_io.h: over the plant server's shared memory in SIL (orccad_io_shm.c), the
 * hardware's on a robot. Each job's measured timing (release lateness, overruns, deadline
 * misses, response time) and outputs are published through them too.
 *
 * The plant server drives the Robot-Tasks' lifecycle over the socket (file descriptor
 * argv[2]): START (fresh Module-Task, nominal parameters), PARAM (a type-1 update), INIT,
 * ACTIVATE (first release at a given instant), KILL, RESET (its ports' values dropped), PING
 * (the heartbeat) and QUIT, with the frames of orccad_lockstep.c. Commands and jobs take one
 * runtime lock: a command is applied between two jobs. The commands' thread runs under
 * SCHED_FIFO too (priority 70) when the processor threads do: a supervisor waiting for an
 * answer holds the plant.
 *
 * C99 + POSIX threads; no allocation after start, no recursion. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <fcntl.h>
#include <pthread.h>
#include <sched.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "orccad_io.h"
#include "orccad_mt.h"

enum { OP_HELLO = 1, OP_START = 2, OP_PARAM = 3, OP_INIT = 4, OP_PING = 6, OP_QUIT = 7,
       OP_ACTIVATE = 8, OP_KILL = 9, OP_RESET = 10, OP_EPOCH = 11 };

#define MAX_MODULES 64
#define MAX_CONNECTIONS 256
#define MAX_PROCESSORS 16
#define MAX_DOUBLES (ORC_MAX_PARAMS + ORC_MAX_PORTS * (ORC_MAX_DIM + 1))

typedef struct {
    uint32_t op, module;
    double t_s;
    uint32_t n, offset;
} request_t;

typedef struct {
    uint32_t status, n;
} reply_t;

/* The state of one Module-Task in the runtime. */
typedef struct {
    int active;
    int64_t next_release_ns;  /* absolute, CLOCK_MONOTONIC; INT64_MAX: none due (sporadic) */
    int64_t last_release_ns;  /* sporadic: the previous release (INT64_MIN: none yet) */
    int64_t released, overruns, misses, events;
    double response_max_ns;
} rt_task;

/* An asyn/asyn buffer of one connection. */
typedef struct {
    int present;
    double v[ORC_MAX_DIM];
} rt_buffer;

static pthread_mutex_t rt_lock = PTHREAD_MUTEX_INITIALIZER;
static rt_task tasks[MAX_MODULES];
static rt_buffer buffers[MAX_CONNECTIONS];
static volatile int stopping;
static int64_t epoch_ns;
static double data_in[MAX_DOUBLES];

static int64_t now_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (int64_t)ts.tv_sec * 1000000000LL + ts.tv_nsec;
}

/* ---- I/O: orccad_io.h (the SIL implementation: orccad_io_shm.c) ---------------------- */

/* ---- one job ----------------------------------------------------------------------------- */

static void read_inputs(int m)
{
    orc_mt *mt = &ORC_INSTANCES[m];
    int c, s;
    for (s = 0; s < mt->n_in; s++) {
        mt->in[s].present = 0;
    }
    for (c = 0; c < ORC_N_CONNECTIONS; c++) {
        const orc_connection *k = &ORC_CONNECTIONS[c];
        orc_value *slot;
        if (k->dst_module != m) {
            continue;
        }
        slot = &mt->in[k->dst_slot];
        if (k->src_module < 0) {
            orc_io_read_sensor(k->src_slot, slot);
        } else {
            slot->present = buffers[c].present;
            memcpy(slot->v, buffers[c].v, sizeof slot->v);
        }
    }
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

static int is_observer(int kind)
{
    return (kind >= ORC_OBS_JOINT_LIMITS && kind <= ORC_OBS_AT_REST) || kind == ORC_AUV_OBSERVER;
}

static void write_outputs(int m)
{
    orc_mt *mt = &ORC_INSTANCES[m];
    int c;
    for (c = 0; c < ORC_N_CONNECTIONS; c++) {
        const orc_connection *k = &ORC_CONNECTIONS[c];
        const orc_value *out;
        if (k->src_module != m || !mt->out[k->src_slot].present) {
            continue;
        }
        out = &mt->out[k->src_slot];
        if (k->dst_module < 0) {
            orc_io_write_actuator(k->dst_slot, out);
        } else {
            buffers[c].present = 1;
            memcpy(buffers[c].v, out->v, sizeof buffers[c].v);
            if (ORC_MODULES[k->dst_module].sporadic) {
                interrupt(k->dst_module);
            }
        }
    }
    if (is_observer(ORC_MODULES[m].kind) && mt->out[0].present) {
        tasks[m].events += 1; /* an observer's event (slot 0): counted for the plant server */
    }
}

static void run_job(int m, int64_t release_ns, int64_t woke_ns)
{
    const orc_mt_def *def = &ORC_MODULES[m];
    double response;
    tasks[m].released += 1;
    orc_io_lateness(m, (double)(woke_ns - release_ns));
    read_inputs(m);
    orc_mt_compute(&ORC_INSTANCES[m], (double)(release_ns - epoch_ns) * 1e-9);
    write_outputs(m);
    response = (double)(now_ns() - release_ns);
    if (response > tasks[m].response_max_ns) {
        tasks[m].response_max_ns = response;
    }
    if (response > (double)def->period_ns) {
        tasks[m].misses += 1;
    }
    orc_io_publish(m, &ORC_INSTANCES[m], tasks[m].released, tasks[m].overruns, tasks[m].misses,
                   tasks[m].events, tasks[m].response_max_ns);
}

/* ---- processor threads ------------------------------------------------------------------- */

static int has_sporadic(int processor)
{
    int m, found = 0;
    pthread_mutex_lock(&rt_lock);
    for (m = 0; m < ORC_N_MODULES; m++) {
        found |= tasks[m].active && ORC_MODULES[m].sporadic
                 && ORC_MODULES[m].processor == processor;
    }
    pthread_mutex_unlock(&rt_lock);
    return found;
}

static void *processor_thread(void *arg)
{
    int processor = (int)(intptr_t)arg;
    while (!stopping) {
        int64_t next = INT64_MAX, woke;
        int m, priority;
        struct timespec ts;
        pthread_mutex_lock(&rt_lock);
        for (m = 0; m < ORC_N_MODULES; m++) {
            if (tasks[m].active && ORC_MODULES[m].processor == processor
                && tasks[m].next_release_ns < next) {
                next = tasks[m].next_release_ns;
            }
        }
        pthread_mutex_unlock(&rt_lock);
        if (next == INT64_MAX) { /* nothing due here: look again in 200 µs */
            next = now_ns() + 200000;
        }
        if (has_sporadic(processor) && next > now_ns() + 100000) {
            next = now_ns() + 100000; /* an interrupt from another thread: seen in 100 µs */
        }
        ts.tv_sec = (time_t)(next / 1000000000LL);
        ts.tv_nsec = (long)(next % 1000000000LL);
        while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, NULL) == EINTR) {
        }
        woke = now_ns();
        pthread_mutex_lock(&rt_lock);
        for (priority = 1; priority <= 99; priority++) { /* jobs in priority order */
            for (m = 0; m < ORC_N_MODULES; m++) {
                rt_task *t = &tasks[m];
                int64_t period = ORC_MODULES[m].period_ns, release;
                if (!t->active || ORC_MODULES[m].processor != processor
                    || ORC_MODULES[m].priority != priority || t->next_release_ns > woke) {
                    continue;
                }
                release = t->next_release_ns;
                run_job(m, release, woke);
                if (ORC_MODULES[m].sporadic) { /* the next release comes from an interrupt */
                    t->last_release_ns = release;
                    t->next_release_ns = INT64_MAX;
                    continue;
                }
                t->next_release_ns = release + period;
                while (t->next_release_ns <= now_ns()) { /* releases missed: overruns */
                    t->overruns += 1;
                    t->next_release_ns += period;
                }
            }
        }
        pthread_mutex_unlock(&rt_lock);
    }
    return NULL;
}

static int start_thread(pthread_t *thread, int processor, int *warned)
{
    pthread_attr_t attr;
    struct sched_param param;
    int m, best = 99, error;
    for (m = 0; m < ORC_N_MODULES; m++) {
        if (ORC_MODULES[m].processor == processor && ORC_MODULES[m].priority < best) {
            best = ORC_MODULES[m].priority;
        }
    }
    pthread_attr_init(&attr);
    pthread_attr_setinheritsched(&attr, PTHREAD_EXPLICIT_SCHED);
    pthread_attr_setschedpolicy(&attr, SCHED_FIFO);
    param.sched_priority = best < 79 ? 80 - best : 1;
    pthread_attr_setschedparam(&attr, &param);
    if (getenv("ORCCAD_NO_FIFO") != NULL) {
        error = EPERM;
    } else {
        error = pthread_create(thread, &attr, processor_thread, (void *)(intptr_t)processor);
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
        error = pthread_create(thread, NULL, processor_thread, (void *)(intptr_t)processor);
    }
    return error;
}

/* ---- the socket: commands and heartbeat --------------------------------------------------- */

static int read_full(int fd, void *buf, size_t size)
{
    char *p = buf;
    while (size > 0) {
        ssize_t got = read(fd, p, size);
        if (got == 0 || (got < 0 && errno != EINTR)) {
            return -1;
        }
        if (got > 0) {
            p += got;
            size -= (size_t)got;
        }
    }
    return 0;
}

static int reply(int fd, uint32_t status, uint32_t n, const double *values)
{
    reply_t head;
    head.status = status;
    head.n = n;
    if (write(fd, &head, sizeof head) != (ssize_t)sizeof head) {
        return -1;
    }
    if (n && write(fd, values, n * sizeof(double)) != (ssize_t)(n * sizeof(double))) {
        return -1;
    }
    return 0;
}

static void reset_ports(int m)
{
    int c;
    for (c = 0; c < ORC_N_CONNECTIONS; c++) {
        if (ORC_CONNECTIONS[c].src_module == m || ORC_CONNECTIONS[c].dst_module == m) {
            buffers[c].present = 0;
        }
    }
}

static uint32_t command(const request_t *req, double *answer, uint32_t *n)
{
    orc_mt *mt;
    *n = 0;
    if (req->op == OP_HELLO) {
        size_t len = strlen(ORC_TABLE_DIGEST);
        memset(answer, 0, 9 * sizeof(double));
        answer[0] = (double)ORC_N_MODULES;
        memcpy(&answer[1], ORC_TABLE_DIGEST, len < 64 ? len : 64);
        *n = 9;
        return 0;
    }
    if (req->op == OP_PING) {
        return 0;
    }
    if (req->op == OP_EPOCH) { /* the I/O side's t = 0 (SIL: the plant server's) */
        epoch_ns = orc_io_epoch_ns(epoch_ns);
        return 0;
    }
    if (req->module >= (uint32_t)ORC_N_MODULES) {
        return 1;
    }
    mt = &ORC_INSTANCES[req->module];
    switch (req->op) {
    case OP_START:
        orc_mt_load(mt, &ORC_MODULES[req->module]);
        orc_mt_init(mt);
        return 0;
    case OP_PARAM:
        return orc_mt_set_param(mt, (int)req->offset, data_in, (int)req->n) ? 2 : 0;
    case OP_INIT:
        orc_mt_init(mt);
        return 0;
    case OP_ACTIVATE: { /* first release at epoch + t_s, or now when that has passed (the
                         * plant server behind the wall clock is not the threads' lateness) */
        int64_t at = epoch_ns + (int64_t)(req->t_s * 1e9 + 0.5), now = now_ns();
        orc_mt_init(mt);
        tasks[req->module].active = 1;
        tasks[req->module].next_release_ns = at > now ? at : now;
        if (ORC_MODULES[req->module].sporadic) { /* released by its first interrupt */
            tasks[req->module].next_release_ns = INT64_MAX;
            tasks[req->module].last_release_ns = INT64_MIN;
        }
        return 0;
    }
    case OP_KILL:
        tasks[req->module].active = 0;
        return 0;
    case OP_RESET:
        reset_ports((int)req->module);
        return 0;
    default:
        return 4;
    }
}

int main(int argc, char **argv)
{
    pthread_t threads[MAX_PROCESSORS];
    int fd, p, warned = 0, status = 0;
    request_t req;
    double answer[9];
    if (argc != 5 || strcmp(argv[1], "--fd") != 0 || strcmp(argv[3], "--io") != 0) {
        fprintf(stderr, "usage: %s --fd N --io WHERE (started by orccad sil --realtime)\n",
                argv[0]);
        return 2;
    }
    if (ORC_N_MODULES > MAX_MODULES || ORC_N_CONNECTIONS > MAX_CONNECTIONS
        || ORC_N_PROCESSORS > MAX_PROCESSORS) {
        fprintf(stderr, "orccad_rt: the table exceeds the runtime's sizes\n");
        return 2;
    }
    fd = atoi(argv[2]);
    if (orc_io_open(argv[4]) != 0) {
        fprintf(stderr, "orccad_rt: the robot's I/O cannot start (%s)\n", argv[4]);
        return 2;
    }
    epoch_ns = now_ns();
    for (p = 0; p < ORC_N_PROCESSORS; p++) {
        if (start_thread(&threads[p], p, &warned) != 0) {
            fprintf(stderr, "orccad_rt: cannot start the thread of processor %d\n", p);
            return 2;
        }
    }
    if (!warned) { /* the commands' thread: above the plant server, below the processors */
        struct sched_param command_param;
        command_param.sched_priority = 70;
        (void)pthread_setschedparam(pthread_self(), SCHED_FIFO, &command_param);
    }
    for (;;) {
        uint32_t n, code;
        if (read_full(fd, &req, sizeof req) != 0 || req.n > MAX_DOUBLES
            || read_full(fd, data_in, req.n * sizeof(double)) != 0) {
            break; /* the plant server is gone */
        }
        if (req.op == OP_QUIT) {
            reply(fd, 0, 0, NULL);
            break;
        }
        pthread_mutex_lock(&rt_lock);
        code = command(&req, answer, &n);
        pthread_mutex_unlock(&rt_lock);
        if (reply(fd, code, n, answer) != 0) {
            status = 3;
            break;
        }
    }
    stopping = 1;
    for (p = 0; p < ORC_N_PROCESSORS; p++) {
        pthread_join(threads[p], NULL);
    }
    return status;
}
